// Converts the npm "bunny" package (a CommonJS module exporting `positions`, an array of
// [x, y, z], and `cells`, an array of [i, j, k]) into an ASCII PLY file on standard output,
// so the project's own PLY reader can load it.
// usage: node tools/eval/bunny-to-ply.js PATH/TO/bunny/package > bunny.ply
"use strict";
const path = require("path");
const dir = process.argv[2];
if (!dir) {
  process.stderr.write("usage: bunny-to-ply.js PACKAGE_DIR\n");
  process.exit(2);
}
const bunny = require(path.resolve(dir));
const { positions, cells } = bunny;
if (!Array.isArray(positions) || !Array.isArray(cells)) {
  process.stderr.write(`${dir}: no positions/cells arrays exported\n`);
  process.exit(1);
}
const out = [
  "ply",
  "format ascii 1.0",
  "comment Stanford bunny, from the npm package 'bunny'",
  `element vertex ${positions.length}`,
  "property float x",
  "property float y",
  "property float z",
  `element face ${cells.length}`,
  "property list uchar int vertex_indices",
  "end_header",
];
for (const p of positions) out.push(p.join(" "));
for (const c of cells) out.push(`${c.length} ${c.join(" ")}`);
process.stdout.write(out.join("\n") + "\n");
