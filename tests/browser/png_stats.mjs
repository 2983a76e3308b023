// Is a PNG screenshot more than a blank page? Node's standard library only.
//   node png_stats.mjs SHOT.png
// Prints the image's size, distinct colours and the shares of non-white and
// of coloured (saturated) pixels; exits 1 when the image looks blank: fewer
// than 16 colours, under 0.5 % of the pixels non-white or no coloured pixel.
import { readFileSync } from 'node:fs';
import { inflateSync } from 'node:zlib';

function fail(message) {
  console.error(`png_stats: ${message}`);
  process.exit(1);
}

function decode(buf) {
  const signature = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  if (buf.length < 8 || !buf.subarray(0, 8).equals(signature)) fail('not a PNG file');
  let width = 0, height = 0, depth = 0, type = 0, interlace = 0;
  const idat = [];
  for (let at = 8; at + 8 <= buf.length;) {
    const length = buf.readUInt32BE(at);
    const name = buf.toString('latin1', at + 4, at + 8);
    const data = buf.subarray(at + 8, at + 8 + length);
    if (name === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      depth = data[8];
      type = data[9];
      interlace = data[12];
    } else if (name === 'IDAT') {
      idat.push(data);
    } else if (name === 'IEND') {
      break;
    }
    at += 12 + length;
  }
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[type];
  if (depth !== 8 || channels === undefined || interlace !== 0)
    fail(`unsupported PNG (bit depth ${depth}, colour type ${type}, interlace ${interlace})`);
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  if (raw.length < height * (stride + 1)) fail('truncated image data');
  const px = Buffer.alloc(height * stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const src = y * (stride + 1) + 1, dst = y * stride, up = dst - stride;
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? px[dst + i - channels] : 0;
      const b = y > 0 ? px[up + i] : 0;
      const c = y > 0 && i >= channels ? px[up + i - channels] : 0;
      let p = 0;
      switch (filter) {
        case 0: p = 0; break;
        case 1: p = a; break;
        case 2: p = b; break;
        case 3: p = (a + b) >> 1; break;
        case 4: {
          const q = a + b - c, pa = Math.abs(q - a), pb = Math.abs(q - b), pc = Math.abs(q - c);
          p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default: fail(`bad filter ${filter} in row ${y}`);
      }
      px[dst + i] = (raw[src + i] + p) & 0xff;
    }
  }
  return { width, height, channels, px };
}

const file = process.argv[2];
if (!file) fail('usage: node png_stats.mjs SHOT.png');
const { width, height, channels, px } = decode(readFileSync(file));
const colours = new Set();
let nonWhite = 0, coloured = 0;
for (let i = 0; i < px.length; i += channels) {
  const r = px[i], g = channels >= 3 ? px[i + 1] : r, b = channels >= 3 ? px[i + 2] : r;
  colours.add((r << 16) | (g << 8) | b);
  if (r < 245 || g < 245 || b < 245) ++nonWhite;
  if (Math.max(r, g, b) - Math.min(r, g, b) > 60) ++coloured;
}
const n = width * height;
const stats = `${width}x${height}, ${colours.size} colours, ${(100 * nonWhite / n).toFixed(2)} % non-white, ` +
              `${(100 * coloured / n).toFixed(2)} % coloured`;
console.log(stats);
if (colours.size < 16 || nonWhite < 0.005 * n || coloured === 0) fail(`the screenshot looks blank (${stats})`);
