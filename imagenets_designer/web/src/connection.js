// The WebSocket link to `imagenets designer` (designer/PROTOCOL.md): requests with ids answered by
// replies, pushes (net, event, files, error) and binary port-data frames.
// A run sends a burst of pushes (an event per block, then the net's state); handled one by one, each
// would re-render the page while the run's preview frame waits behind them. So `net` and `event`
// pushes are held until the next display frame and handed on together (one render), and before
// anything else that arrives, so the order of replies and pushes stays as sent. Port data is not
// held: a preview is drawn as soon as it arrives.
const held = new Set(['net', 'event']);

export class Connection {
  constructor(url) {
    this.url = url;
    this.nextId = 1;
    this.pending = new Map();
    this.listeners = new Map();
    this.holding = [];
    this.open = new Promise((resolve, reject) => {
      this.ws = new WebSocket(url);
      this.ws.binaryType = 'arraybuffer';
      this.ws.onopen = () => resolve();
      this.ws.onerror = () => reject(new Error(`cannot connect to ${url}`));
      this.ws.onclose = () => this.emit('closed', {});
      this.ws.onmessage = (m) => this.receive(m.data);
    });
  }

  on(op, fn) {
    if (!this.listeners.has(op)) this.listeners.set(op, new Set());
    this.listeners.get(op).add(fn);
    return () => this.listeners.get(op).delete(fn);
  }

  emit(op, msg) {
    for (const fn of this.listeners.get(op) || []) fn(msg);
  }

  // Resolves with the reply; rejects with an Error carrying the server's own message.
  async request(op, args = {}) {
    await this.open;
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.ws.send(JSON.stringify({ ...args, op, id }));
    });
  }

  // Hands on the held pushes now (also before a port-data frame is stored: it may belong to a net
  // whose state is still held).
  flush() {
    const msgs = this.holding;
    if (!msgs.length) return;
    this.holding = [];
    for (const msg of msgs) this.emit(msg.op, msg);
  }

  receive(data) {
    if (data instanceof ArrayBuffer) {
      this.emit('data', decodePortData(data));
      return;
    }
    const msg = JSON.parse(data);
    if (held.has(msg.op)) {
      if (!this.holding.length) {
        // A hidden page gets no display frames: the timeout hands the pushes on there.
        const flush = () => { cancelAnimationFrame(frame); clearTimeout(timer); this.flush(); };
        const frame = requestAnimationFrame(flush);
        const timer = setTimeout(flush, 100);
      }
      this.holding.push(msg);
      return;
    }
    this.flush();
    if (msg.op === 'reply' && this.pending.has(msg.id)) {
      const { resolve, reject } = this.pending.get(msg.id);
      this.pending.delete(msg.id);
      if (msg.ok) resolve(msg);
      else reject(new Error(msg.error));
      return;
    }
    this.emit(msg.op, msg);
  }
}

// Binary frame: uint32 LE header length, JSON header, payload.
export function decodePortData(buffer) {
  const view = new DataView(buffer);
  const length = view.getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
  const payload = new Uint8Array(buffer, 4 + length);
  if (header.format === 'json') header.value = JSON.parse(new TextDecoder().decode(payload));
  return { header, payload };
}
