// Raw sensor_msgs/Image pixels (the data dialog's "full" mode): display as RGBA and read the
// value(s) of one pixel in the image's own encoding.
const layouts = {
  mono8: { channels: 1, bytes: 1 }, '8UC1': { channels: 1, bytes: 1 },
  mono16: { channels: 1, bytes: 2 }, '16UC1': { channels: 1, bytes: 2 },
  bgr8: { channels: 3, bytes: 1 }, rgb8: { channels: 3, bytes: 1 }, '8UC3': { channels: 3, bytes: 1 },
  bgra8: { channels: 4, bytes: 1 }, rgba8: { channels: 4, bytes: 1 },
  '32FC1': { channels: 1, bytes: 4, float: true },
};

export function imageLayout(encoding) {
  const layout = layouts[encoding];
  if (!layout) throw new Error(`image encoding '${encoding}' cannot be shown`);
  return layout;
}

// A reader of the value(s) at (x, y), as numbers, in the message's channel order.
export function pixelReader(header, payload) {
  const { channels, bytes, float } = imageLayout(header.encoding);
  const view = new DataView(payload.buffer, payload.byteOffset, payload.byteLength);
  const little = !header.is_bigendian;
  return (x, y) => {
    const offset = y * header.step + x * channels * bytes;
    const values = [];
    for (let c = 0; c < channels; ++c) {
      const at = offset + c * bytes;
      if (float) values.push(view.getFloat32(at, little));
      else if (bytes === 2) values.push(view.getUint16(at, little));
      else values.push(view.getUint8(at));
    }
    return values;
  };
}

export function pixelValues(header, payload, x, y) {
  return pixelReader(header, payload)(x, y);
}

// RGBA for display; 16-bit and float images are stretched over their finite min..max.
export function toImageData(header, payload) {
  const { width, height, encoding } = header;
  const { channels } = imageLayout(encoding);
  const out = new ImageData(width, height);
  const values = pixelReader(header, payload);
  let lo = 0, hi = 255;
  if (encoding === 'mono16' || encoding === '16UC1' || encoding === '32FC1') {
    lo = Infinity; hi = -Infinity;
    for (let y = 0; y < height; ++y) for (let x = 0; x < width; ++x) {
      const v = values(x, y)[0];
      if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    }
    if (!(hi > lo)) { hi = lo + 1; }
  }
  const scale = 255 / (hi - lo);
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      const v = values(x, y);
      const i = 4 * (y * width + x);
      if (channels === 1) {
        const g = Number.isFinite(v[0]) ? (v[0] - lo) * scale : 0;
        out.data[i] = out.data[i + 1] = out.data[i + 2] = g;
      } else {
        const bgr = encoding.startsWith('bgr') || encoding === '8UC3';
        out.data[i] = bgr ? v[2] : v[0];
        out.data[i + 1] = v[1];
        out.data[i + 2] = bgr ? v[0] : v[2];
      }
      out.data[i + 3] = 255;
    }
  }
  return out;
}
