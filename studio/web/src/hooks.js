// Calls that go up the module graph, filled in by studio.js at start-up: the editor compiles and saves,
// and a slider's or a dragged patch's answer is applied, from modules that compiling itself imports.
export const hooks = { compileNow: null, flushCompile: null, save: null, applyCompile: null };
