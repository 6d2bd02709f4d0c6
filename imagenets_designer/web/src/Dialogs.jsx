import React, { useEffect, useMemo, useState } from 'react';
import { matchBlocks } from './BlockBrowser.jsx';

export function Modal({ title, onClose, children, wide, testid }) {
  useEffect(() => {
    const key = (e) => { if (e.key === 'Escape') onClose(); };
    window.addEventListener('keydown', key);
    return () => window.removeEventListener('keydown', key);
  }, [onClose]);
  return (
    <div className="modal-backdrop" onMouseDown={(e) => { if (e.target === e.currentTarget) onClose(); }}>
      <div className={`modal ${wide ? 'wide' : ''}`} data-testid={testid}>
        <div className="modal-title">{title}<button className="close" onClick={onClose}>✕</button></div>
        <div className="modal-body">{children}</div>
      </div>
    </div>
  );
}

// Double-click on the canvas, or a link dropped on empty canvas: pick a block by name.
// With `inputType`, only blocks with an input of that type are offered.
export function BlockSearch({ registry, inputType, at, onPick, onClose }) {
  const [text, setText] = useState('');
  const list = useMemo(() => matchBlocks(registry.blocks, { text, input: inputType || '' }), [registry, text, inputType]);
  return (
    <div className="block-search" style={{ left: at.x, top: at.y }} data-testid="block-search-popup">
      <input autoFocus placeholder={inputType ? `blocks taking ${inputType}` : 'add block'} value={text}
        onChange={(e) => setText(e.target.value)}
        onKeyDown={(e) => {
          if (e.key === 'Escape') onClose();
          if (e.key === 'Enter' && list.length) onPick(list[0].type);
        }} />
      <div className="search-results">
        {list.map((b) => (
          <div key={b.type} className="search-result" data-type={b.type} title={b.doc}
            onMouseDown={(e) => { e.preventDefault(); onPick(b.type); }}>
            {b.type.replace(/^imagenets\//, '')} <span className="category">{b.category}</span>
          </div>
        ))}
      </div>
    </div>
  );
}

// Open / save as: a path field, the folders the designer may read and write (the net's folder,
// imagenets_blocks' config/, each --root), and the server's listing of a folder among them.
export function FileDialog({ title, initialPath, request, onDone, onClose }) {
  const [path, setPath] = useState(initialPath || '');
  const [listing, setListing] = useState(null);
  const [roots, setRoots] = useState([]);
  const [error, setError] = useState(null);
  const list = async (dir) => {
    try {
      const r = await request('list_files', dir ? { dir } : {});
      setListing(r);
      setRoots(r.roots || []);
      setError(null);
      return true;
    } catch (err) { setError(err.message); return false; }
  };
  // A folder outside the allowed ones lists the net's folder instead (and says why).
  useEffect(() => {
    const dir = initialPath ? initialPath.replace(/\/[^/]*$/, '') : undefined;
    list(dir).then((ok) => { if (!ok && dir) list(); });
  }, []);
  const submit = async () => {
    try { await onDone(path); onClose(); } catch (err) { setError(err.message); }
  };
  return (
    <Modal title={title} onClose={onClose} testid="file-dialog">
      <div className="file-path">
        <input data-testid="file-path" value={path} onChange={(e) => setPath(e.target.value)}
          onKeyDown={(e) => { if (e.key === 'Enter') submit(); }} />
        <button data-testid="file-ok" onClick={submit}>{title}</button>
      </div>
      {error && <div className="error" data-testid="file-error">{error}</div>}
      {roots.length > 0 && <div className="file-roots" data-testid="file-roots">
        <div className="file-roots-head">allowed folders (start the designer with --root DIR for another):</div>
        {roots.map((r) => (
          <div key={r} className={`file-root ${listing?.dir === r ? 'current' : ''}`} data-root={r} onClick={() => list(r)}>{r}/</div>
        ))}
      </div>}
      {listing && <div className="file-list">
        <div className="file-dir">{listing.dir}</div>
        {!roots.includes(listing.dir) && <div className="file-entry dir" onClick={() => list(`${listing.dir}/..`)}>..</div>}
        {listing.entries.map((e) => (
          <div key={e.name} className={`file-entry ${e.dir ? 'dir' : ''}`}
            onClick={() => (e.dir ? list(`${listing.dir}/${e.name}`) : setPath(`${listing.dir}/${e.name}`))}>
            {e.name}{e.dir ? '/' : ''}
          </div>
        ))}
      </div>}
    </Modal>
  );
}

// Exported launch file or Graphviz picture, shown and offered as a download.
export function ExportDialog({ title, text, svg, fileName, onClose }) {
  const url = useMemo(() => URL.createObjectURL(new Blob([svg || text], { type: svg ? 'image/svg+xml' : 'text/xml' })), [svg, text]);
  useEffect(() => () => URL.revokeObjectURL(url), [url]);
  return (
    <Modal title={title} onClose={onClose} wide testid="export-dialog">
      <a href={url} download={fileName}>download {fileName}</a>
      {svg ? <div className="export-svg" dangerouslySetInnerHTML={{ __html: svg }} />
        : <pre className="export-text">{text}</pre>}
    </Modal>
  );
}
