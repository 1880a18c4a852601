#!/usr/bin/env node
// Runs a G-code program through gcode-toolpath (the interpreter behind
// CNCjs) and prints every motion it produces as one JSON document:
//   {"file": ..., "motions": [{"type": "line"|"arc", "motion": "G0".."G3",
//     "start": [x,y,z], "end": [x,y,z], "center": [x,y,z] (arcs), "plane": "G17",
//     "units": "G21"|"G20", "feed": F or null, "line": n, "comment": "..." (on its line),
//     "section": "..." (the last comment standing on a line of its own)}],
//    "unknown": [{"line": n, "code": "G41"}], "modal": {...final modal state}}
// Positions are in millimetres whatever the program's units (the interpreter
// converts G20 inches). "unknown" lists G and M codes the interpreter has no
// handler for (it would skip them silently). Usage: node gcode-trace.js FILE.nc
'use strict';

const fs = require('fs');
const Toolpath = require('gcode-toolpath');

const HANDLED = new Set([
  'G0', 'G1', 'G2', 'G3', 'G4', 'G10', 'G17', 'G18', 'G19', 'G20', 'G21', 'G38.2', 'G38.3', 'G38.4', 'G38.5',
  'G43.1', 'G49', 'G54', 'G55', 'G56', 'G57', 'G58', 'G59', 'G80', 'G90', 'G91', 'G92', 'G92.1', 'G93', 'G94',
  'G95', 'M0', 'M1', 'M2', 'M3', 'M4', 'M5', 'M6', 'M7', 'M8', 'M9', 'M30',
]);

function point(v) {
  return [v.x, v.y, v.z];
}

function main() {
  const file = process.argv[2];
  if (!file) {
    process.stderr.write('usage: node gcode-trace.js FILE.nc\n');
    process.exit(2);
  }
  const text = fs.readFileSync(file, 'utf8');
  const motions = [];
  const unknown = [];
  let pending = [];
  const toolpath = new Toolpath({
    addLine: (modal, v1, v2) => {
      pending.push({
        type: 'line', motion: modal.motion, start: point(v1), end: point(v2), plane: modal.plane,
        units: modal.units,
      });
    },
    addArcCurve: (modal, v1, v2, v0) => {
      pending.push({
        type: 'arc', motion: modal.motion, start: point(v1), end: point(v2), center: point(v0),
        plane: modal.plane, units: modal.units,
      });
    },
  });
  let feed = null;
  let section = '';
  let lineNumber = 0;
  toolpath.loadFromStringSync(text, (data) => {
    ++lineNumber;
    for (const [letter, value] of data.words) {
      if (letter === 'F') feed = value;
      if (letter === 'G' || letter === 'M') {
        const code = letter + value;
        if (!HANDLED.has(code)) unknown.push({ line: lineNumber, code });
      }
    }
    const comment = data.comments ? data.comments.join(' ') : '';
    if (comment && data.words.length === 0) section = comment;
    for (const m of pending) {
      m.line = lineNumber;
      m.feed = feed;
      if (comment) m.comment = comment;
      m.section = section;
      motions.push(m);
    }
    pending = [];
  });
  process.stdout.write(`${JSON.stringify({ file, motions, unknown, modal: toolpath.getModal() })}\n`);
}

try {
  main();
} catch (err) {
  process.stderr.write(`gcode-trace: ${err && err.stack ? err.stack : err}\n`);
  process.exit(1);
}
