// The types of ./arena-sdk.mjs, the SDK's bundle served beside page.mjs: its sources, so that
// tsc checks the page against the SDK as it is (esbuild leaves the import to run time).
export * from '../../sdk/src/index.js';
