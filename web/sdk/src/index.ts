// Arena's browser SDK: the client core in WebAssembly and what a game draws with.
export { Core, Payload } from './core.js';
export type { BodyState, Shape, StaticBody, ReplayResult, CoreModuleOptions } from './core.js';
export { CoreSession } from './session.js';
export type { PredictedBody } from './session.js';
