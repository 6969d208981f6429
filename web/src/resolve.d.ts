// TypeScript declarations of cloudmath-glsl/resolve (src/resolve.js, written by hand: keep
// the two in step; web/test/pack.sh checks that every export of resolve.js is declared here
// and type-checks a use of it with tsc).

/** Options of resolveIncludes. */
export interface ResolveIncludesOptions {
  /** The name of `source` in error messages (default "<source>"). */
  name?: string;
}

/**
 * Replaces every line `#include "name"` (or `<name>`) of `source` by the text of `files[name]`
 * (looked up as written, then without leading directories), recursively; each file is
 * inserted once. Throws an Error naming the file and line of a missing include or a cycle,
 * and a TypeError when `source` is not a string.
 */
export declare function resolveIncludes(
  source: string,
  files?: Readonly<Record<string, string>>,
  options?: ResolveIncludesOptions,
): string;
