// Arena's browser SDK: the client core in WebAssembly and what a game draws with.
export { connect, ArenaClient, PROTOCOL_ERROR_CLOSE_CODE, momentOf } from './client.js';
export { listModes, listMatches, getMatch, createMatch, joinOrCreate, join, create } from './lobby.js';
export type { ModeInfo, MatchInfo, LobbyOptions } from './lobby.js';
export type { ConnectOptions, SocketLike, Welcome, SnapshotEvent, DrawBody, RenderState, ViewMoment, SentInput } from './client.js';
export { Core, Payload } from './core.js';
export type { BodyState, Shape, StaticBody, ReplayResult, CoreModuleOptions } from './core.js';
export { ReplayPlayer } from './player.js';
export type { PlayerBody, ReplayLine, ReplayTeam, MatchResult } from './player.js';
export { CoreSession } from './session.js';
export type { OwnBullet, PredictedBody } from './session.js';
export { Interpolator, shortest, wrapAngle } from './interpolation.js';
export type { InterpolationOptions, Sampled } from './interpolation.js';
export { CorrectionSmoother } from './smoothing.js';
export type { SmoothingOptions } from './smoothing.js';
export { readMessage, decodeManifest } from './messages.js';
export * as protocol from '@arena/protocol';
export type { PlayerLine, GameEvent, ByeFields, WelcomeFields, GameManifest, GameField, GameValue, GameRecord } from './messages.js';
