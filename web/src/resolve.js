// cloudmath-glsl/resolve: a small #include resolver for GLSL sources held as strings.
//
//   import { resolveIncludes } from 'cloudmath-glsl/resolve';
//   const glsl = resolveIncludes(mySource, { 'lighting.glsl': lightingSource, ...sources });
//
// Every line of the form   #include "name"   (or <name>) is replaced by the text of the file
// `name`, resolved the same way, recursively. A file is inserted at most once per call (the
// cloudmath files also carry include guards); later includes of it become a comment. Names
// are looked up as written, then without any leading directories, so
// "cloudmath/glsl/phase.glsl" finds "phase.glsl". A missing file or an include cycle throws
// an Error that names the file and the line that asked for it. Nothing else is touched:
// #define configuration placed before an include keeps working.

const includeLine = /^[ \t]*#[ \t]*include[ \t]*(?:"([^"]+)"|<([^>]+)>)[ \t]*(?:\/\/.*)?$/;

function lookup(files, name) {
  if (Object.prototype.hasOwnProperty.call(files, name)) return name;
  const base = name.split('/').pop();
  if (Object.prototype.hasOwnProperty.call(files, base)) return base;
  return null;
}

export function resolveIncludes(source, files = {}, options = {}) {
  if (typeof source !== 'string') throw new TypeError('resolveIncludes: source must be a string');
  const seen = new Set();
  const stack = [];
  const from = options.name || '<source>';
  function expand(text, name) {
    stack.push(name);
    const out = text.split('\n').map((line, index) => {
      const m = includeLine.exec(line);
      if (!m) return line;
      const wanted = m[1] || m[2];
      const key = lookup(files, wanted);
      if (key === null)
        throw new Error(`${name}:${index + 1}: #include "${wanted}": no such file among ${Object.keys(files).length} known`);
      if (stack.includes(key))
        throw new Error(`${name}:${index + 1}: #include "${wanted}": include cycle ${stack.join(' -> ')} -> ${key}`);
      if (seen.has(key)) return `// #include "${wanted}" (already included above)`;
      seen.add(key);
      return expand(files[key], key);
    });
    stack.pop();
    return out.join('\n');
  }
  return expand(source, from);
}
