import React from 'react';
import { BaseEdge, EdgeLabelRenderer, getBezierPath } from '@xyflow/react';
import { FEEDBACK_COLOR } from './flow.js';

// Which score drives a block's feedback (paper Fig. 3.3): dashed, from the score port back to the
// block, labelled with the tuned property and the goal, as `imagenets graph` draws it.
export function FeedbackEdge({ id, sourceX, sourceY, targetX, targetY, sourcePosition, targetPosition, data, selected }) {
  const [path, labelX, labelY] = getBezierPath({ sourceX, sourceY, sourcePosition, targetX, targetY, targetPosition });
  const fb = data.feedback;
  const label = `feedback: ${fb.property} (${fb.goal === 'minimize' ? 'min' : 'max'} ${fb.score})`;
  return (
    <>
      <BaseEdge id={id} path={path} className="feedback-edge-path"
        style={{ stroke: FEEDBACK_COLOR, strokeWidth: selected ? 3 : 2, strokeDasharray: '7 5' }} />
      <EdgeLabelRenderer>
        <div className={`feedback-edge-label nodrag nopan ${selected ? 'selected' : ''}`} data-block={data.block}
          style={{ transform: `translate(-50%, -50%) translate(${labelX}px, ${labelY}px)` }}
          title="drag the edge's end at the score port onto another std_msgs/Float64 output to score by it">
          {label}
        </div>
      </EdgeLabelRenderer>
    </>
  );
}
