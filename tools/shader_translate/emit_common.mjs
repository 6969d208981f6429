// tools/shader_translate/emit_common.mjs: what both emitters share: comment placement and
// the walk over top-level items with their indentation.

export const INDENT = '    ';

// Comments of a node (leading lines, then the node's text, then its trailing comment).
export function withComments(node, text, indent, rewrite = (c) => c) {
  const lead = (node.leading || []).map((c) => rewrite(c).split('\n').map((l, i) => (i === 0 ? indent + l : l)).join('\n'));
  const trail = node.trailing ? ` ${rewrite(node.trailing)}` : '';
  return [...lead, text + trail].join('\n');
}

// Joins printed top-level items, keeping one blank line where the source had one (an item
// whose line is more than one past the previous item's end), so the output reads like the
// GLSL it came from.
export function joinItems(printed) {
  let out = '';
  for (const { text, blankBefore } of printed) {
    if (!text) continue;
    if (out && blankBefore) out += '\n';
    out += text + '\n';
  }
  return out;
}

// A function body of one short statement printed on the line of its head, as the GLSL
// writes cm_saturate: "{\n    return x;\n}" -> "{ return x; }" when the line stays short.
export function oneLine(head, block) {
  const m = /^\{\n {4}([^\n]*)\n\}$/.exec(block);
  if (m && !m[1].startsWith('//') && !m[1].includes(' //') && head.length + m[1].length < 112) return `${head} { ${m[1]} }`;
  return `${head} ${block}`;
}
