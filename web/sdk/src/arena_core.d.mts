// Types of the loader emscripten generates for the client core (arena_core.mjs, built from
// web/sdk/core/ and shipped beside the bundle). Only what the SDK uses; pointers are numbers.
export interface CoreModuleOptions {
  /** The .wasm bytes, when the loader should not fetch them (Node, or a bundler's asset). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** Where arena_core.wasm is, when it is not beside arena_core.mjs. */
  locateFile?: (path: string, prefix: string) => string;
}

export interface CoreModule {
  HEAPU8: Uint8Array;
  FS: { writeFile(path: string, data: Uint8Array): void; unlink(path: string): void };
  UTF8ToString(pointer: number): string;
  stringToUTF8(text: string, pointer: number, maxBytes: number): void;
  lengthBytesUTF8(text: string): number;
  _malloc(size: number): number;
  _free(pointer: number): void;

  _arena_session_new(deltaSnapshots: number, spectator: number): number;
  _arena_session_free(session: number): void;
  _arena_feed(session: number, data: number, size: number): number;
  _arena_ended(session: number): number;
  _arena_error(session: number): number;
  _arena_hello(session: number, name: number, token: number): number;
  _arena_hello_to(session: number, name: number, token: number, match: number, mode: number): number;
  _arena_set_view_moment(session: number, tick: number, fraction: number): void;
  _arena_input(session: number, thrust: number, turn: number, buttons: number): number;
  _arena_ping(session: number, clientTime: number): number;
  _arena_bye(session: number, reason: number): number;
  _arena_out(session: number): number;
  _arena_player_id(session: number): number;
  _arena_entity_id(session: number): number;
  _arena_tick_rate(session: number): number;
  _arena_snapshot_rate(session: number): number;
  _arena_world_wraps(session: number): number;
  _arena_world_width(session: number): number;
  _arena_world_height(session: number): number;
  _arena_view_tick(session: number): number;
  _arena_view_ack(session: number): number;
  _arena_last_sequence(session: number): number;
  _arena_delta_ack(session: number): number;
  _arena_delta_problem(session: number): number;
  _arena_inputs_left_out(session: number): number;
  _arena_view(session: number): number;
  _arena_view_count(session: number): number;
  _arena_shapes(session: number): number;
  _arena_shape_count(session: number): number;
  _arena_statics(session: number): number;
  _arena_static_count(session: number): number;
  _arena_predicted(session: number): number;
  _arena_own_bullets(session: number): number;
  _arena_own_bullet_count(session: number): number;
  _arena_prediction_error(session: number): number;

  _arena_replay_open(path: number): number;
  _arena_replay_open_error(): number;
  _arena_replay_free(replay: number): void;
  _arena_replay_run(replay: number, until: number): number;
  _arena_replay_dump(replay: number): number;
  _arena_replay_error(replay: number): number;
  _arena_replay_final_tick(replay: number): number;
  _arena_replay_hashes_checked(replay: number): number;
  _arena_replay_final_hash(replay: number): number;
  _arena_replay_bodies(replay: number): number;
  _arena_replay_body_count(replay: number): number;

  _arena_player_open(path: number): number;
  _arena_player_free(player: number): void;
  _arena_player_step(player: number, ticks: number): number;
  _arena_player_seek(player: number, tick: number): number;
  _arena_player_tick(player: number): number;
  _arena_player_start_tick(player: number): number;
  _arena_player_end_tick(player: number): number;
  _arena_player_tick_rate(player: number): number;
  _arena_player_hashes_checked(player: number): number;
  _arena_player_hashes_total(player: number): number;
  _arena_player_hash(player: number): number;
  _arena_player_recorded_hash(player: number): number;
  _arena_player_error(player: number): number;
  _arena_player_cut_short(player: number): number;
  _arena_player_world_config(player: number): number;
  _arena_player_world_wraps(player: number): number;
  _arena_player_world_width(player: number): number;
  _arena_player_world_height(player: number): number;
  _arena_player_bodies(player: number): number;
  _arena_player_body_count(player: number): number;
  _arena_player_shapes(player: number): number;
  _arena_player_manifest(player: number): number;
  _arena_player_manifest_size(player: number): number;
  _arena_player_scoreboard(player: number): number;
  _arena_player_scoreboard_count(player: number): number;
  _arena_player_scoreboard_name(player: number, index: number): number;
  _arena_player_name(player: number, id: number): number;
  _arena_player_teams(player: number): number;
  _arena_player_team_count(player: number): number;
  _arena_player_events(player: number): number;
  _arena_player_event_count(player: number): number;
  _arena_player_finished(player: number): number;
  _arena_player_winning_team(player: number): number;
  _arena_player_winners(player: number): number;
  _arena_player_winner_count(player: number): number;
}

export default function createArenaCore(options?: CoreModuleOptions): Promise<CoreModule>;
