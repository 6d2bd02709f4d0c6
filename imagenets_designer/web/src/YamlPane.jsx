import React, { useRef, useState } from 'react';

// The net as net-file text, live; editing it and applying replaces the net (errors with the line).
export function YamlPane({ net, request }) {
  const [draft, setDraft] = useState(null);
  const [error, setError] = useState(null);
  const area = useRef(null);
  const apply = async () => {
    try {
      await request('set_yaml', { text: draft });
      setDraft(null);
      setError(null);
    } catch (err) {
      setError(err.message);
      const line = /:(\d+):/.exec(err.message);
      if (line) selectLine(area.current, Number(line[1]));
    }
  };
  return (
    <div className="yaml-pane">
      <div className="yaml-head">net file {draft !== null && <>
        <button data-testid="yaml-apply" onClick={apply}>apply</button>
        <button onClick={() => { setDraft(null); setError(null); }}>revert</button></>}
      </div>
      <textarea ref={area} data-testid="yaml" spellCheck={false} value={draft ?? net.yaml}
        onChange={(e) => setDraft(e.target.value)}
        onKeyDown={(e) => { if ((e.ctrlKey || e.metaKey) && e.key === 'Enter') { e.preventDefault(); apply(); } }} />
      {error && <div className="error" data-testid="yaml-error">{error}</div>}
    </div>
  );
}

function selectLine(textarea, line) {
  const lines = textarea.value.split('\n');
  const start = lines.slice(0, line - 1).reduce((n, l) => n + l.length + 1, 0);
  textarea.focus();
  textarea.setSelectionRange(start, start + (lines[line - 1] || '').length);
}
