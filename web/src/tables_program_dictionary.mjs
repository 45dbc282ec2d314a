// TBLS version 9's program dictionary (formats/tbls.md, "Program dictionary";
// lib/subdiv/tables_program_dictionary.cpp): the bases' and chains' programs share their rows and
// weights across the chunk. Each row is a reference to a row written before (or a run of them)
// or a new row, which joins the dictionary; weights come from one palette that new rows extend. Every reference,
// source, slot and weight is checked as the C++ reader checks it.
import { MAX_STENCIL_WEIGHT } from './tables_stream.mjs';

const MAX_ENTRIES_PER_ROW = 16;
const NONE = 0xffffffff;

// One per chunk, in record order.
export function programDictionary() {
  return { start: [0], source: [], weight: [], averaged: [], palette: [] };
}

// A program over `support` points from stream `s` (its varints as writeDictionaryProgram writes
// them): at most `maxRows` rows, `next` next-support rows, phantom control rows only where
// `phantoms`. Returns the program as the version-8 readers do ({rows, start, source, weight,
// averaged, controlRow, nextSupport}).
export function readDictionaryProgram(s, support, maxRows, next, phantoms, d) {
  const rows = s.varint();
  if (rows === 0 || rows > maxRows) s.fail(`bad row count ${rows}`);
  const maxEntries = rows * MAX_ENTRIES_PER_ROW;
  const start = [0], source = [], weight = [], averaged = [];
  for (let row = 0; row < rows;) {
    const code = s.varint(), known = d.averaged.length;
    if (code % 2 === 1) { // rows written before, `back` from the last (a run of them when code & 2): sources checked here
      const back = Math.floor(code / 4), isRun = Math.floor(code / 2) % 2 === 1;
      const extra = isRun ? s.varint() : 0, left = rows - row;
      // A run's length less 2 is stored (one row is h & 3 = 1): 2 rows or more, within the
      // program's rows left and the dictionary's rows from the one named.
      if (isRun && (left < 2 || extra > left - 2)) s.fail(`row ${row} has a bad run length`);
      const run = isRun ? extra + 2 : 1;
      if (back >= known || run > back + 1) s.fail(`row ${row} names a missing dictionary row`);
      const ref = known - 1 - back;
      for (let k = 0; k < run; k++, row++) {
        const from = d.start[ref + k], to = d.start[ref + k + 1];
        if (to - from > maxEntries - source.length) s.fail(`row ${row} has a bad length`);
        for (let e = from; e < to; e++) {
          if (d.source[e] >= support + row) s.fail(`row ${row} reads neither a support point nor an earlier row`);
          source.push(d.source[e]);
          weight.push(d.weight[e]);
        }
        averaged.push(d.averaged[ref + k]);
        start.push(source.length);
      }
      continue;
    }
    {
      const head = code / 2, length = Math.floor(head / 2), avg = head % 2;
      if (length === 0 || length > maxEntries - source.length) s.fail(`row ${row} has a bad length`);
      for (let e = 0; e < length; e++) {
        const x = s.varint();
        if (x >= support + row) s.fail(`row ${row} reads neither a support point nor an earlier row`);
        let w = 1;
        if (!avg) {
          const slot = s.varint();
          if (slot > d.palette.length) s.fail('a weight is not in the palette');
          if (slot === d.palette.length) {
            const v = s.rawFloat();
            if (!(Math.abs(v) <= MAX_STENCIL_WEIGHT)) s.fail('has a bad weight');
            d.palette.push(v);
          }
          w = d.palette[slot];
        }
        source.push(x);
        weight.push(w);
        d.source.push(x);
        d.weight.push(w);
      }
      d.start.push(d.source.length);
      d.averaged.push(avg);
      averaged.push(avg);
    }
    start.push(source.length);
    row++;
  }
  // The control rows (row + 1, 0 a phantom) and the next support's rows, each in
  // bit_width(rows + 1) bits, least significant first, the last byte's spare bits 0 (rows <=
  // maxRows: a few thousand).
  const width = 32 - Math.clz32(rows + 1);
  let pending = 0, bits = 0;
  const take = () => {
    for (; bits < width; bits += 8) pending += s.rawByte() * 2 ** bits;
    const x = pending % 2 ** width;
    pending = Math.floor(pending / 2 ** width);
    bits -= width;
    return x;
  };
  const controlRow = Array.from({ length: 48 }, () => {
    const v = take();
    if (v > rows || (v === 0 && !phantoms)) s.fail('a control point names a missing row');
    return v === 0 ? NONE : v - 1;
  });
  const nextSupport = Array.from({ length: next }, () => {
    const v = take();
    if (v >= rows) s.fail('a support point names a missing row');
    return v;
  });
  if (pending !== 0) s.fail("the packed rows' spare bits are not 0");
  return { rows, start, source, weight, averaged, controlRow, nextSupport };
}
