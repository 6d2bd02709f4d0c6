import React from 'react';

// Why a link (or a feedback score) was refused, whole, where the drag ended: the engine's reason
// names both ports and both types, which a toolbar cut off at the right. Click to dismiss.
export function LinkRefusal({ refusal, onClose }) {
  return (
    <div className="link-refusal" data-testid="link-refusal" role="alert" onClick={onClose}
      style={refusal.at} title="click to dismiss">
      <div className="link-refusal-head">link refused</div>
      {refusal.text}
    </div>
  );
}
