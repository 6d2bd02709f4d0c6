import React from 'react';
import { ReactFlowProvider } from '@xyflow/react';
import { BlockBrowser } from './BlockBrowser.jsx';
import { Canvas } from './Canvas.jsx';
import { Overlays } from './Overlays.jsx';
import { SidePanel } from './SidePanel.jsx';
import { Toolbar } from './Toolbar.jsx';
import { useKeyboard } from './commands.js';
import { DesignerProvider, useStore } from './store.jsx';

// The page's layout; its state is in the store (store.jsx), what the user does in commands.js.
export function App() {
  return <ReactFlowProvider><DesignerProvider><Designer /></DesignerProvider></ReactFlowProvider>;
}

function Designer() {
  const { registry, net, message } = useStore().state;
  useKeyboard();
  if (!registry || !net) {
    return <div className="loading">{message ? message.text : 'connecting to the designer…'}</div>;
  }
  return (
    <div className="designer">
      <Toolbar />
      <div className="main">
        <BlockBrowser />
        <Canvas />
        <SidePanel />
      </div>
      <Overlays />
    </div>
  );
}
