// The lobby of a server that hosts many matches (docs/MATCHES.md): list them, create one, and
// join by id or by mode. `base` is the server's HTTP address ("http://host:8080"); the lobby
// answers on the same port as /ws.
import { ArenaClient, ConnectOptions, connect } from './client.js';

/** One match as GET /matches describes it. */
export interface MatchInfo {
  id: string;
  mode: string;
  players: number;
  capacity: number;
  spectators: number;
  tick: number;
  /** open: a seat is free; full; ending. */
  state: 'open' | 'full' | 'ending';
  /** RFC 3339, UTC ('' for the server's default match when unknown). */
  created: string;
  private: boolean;
}

export interface LobbyOptions {
  /** The fetch to use (default: the global one); tests hand in their own. */
  fetch?: (url: string, init?: { method?: string; headers?: Record<string, string>; body?: string }) => Promise<{ ok: boolean; status: number; text(): Promise<string> }>;
  /** A join token, for a server run with --token-secret (POST /matches needs one). */
  token?: string;
}

async function request<T>(base: string, path: string, options: LobbyOptions, init?: { method: string; body: string }): Promise<T> {
  const f = options.fetch ?? (globalThis.fetch as unknown as NonNullable<LobbyOptions['fetch']>);
  const headers: Record<string, string> = { 'Content-Type': 'application/json' };
  if (options.token) headers.Authorization = `Bearer ${options.token}`;
  const response = await f(`${base.replace(/\/$/, '')}${path}`, { ...init, headers });
  const text = await response.text();
  let body: unknown;
  try {
    body = JSON.parse(text);
  } catch {
    throw new Error(`lobby ${path}: HTTP ${response.status}: ${text.trim()}`);
  }
  if (!response.ok) {
    const why = (body as { error?: string }).error ?? text.trim();
    throw new Error(`lobby ${path}: HTTP ${response.status}: ${why}`);
  }
  return body as T;
}

/** One mode as GET /modes describes it. */
export interface ModeInfo {
  name: string;
  capacity: number;
  preset: string;
  rules: string;
  /** Seconds a match of the mode lasts; 0: no limit. */
  duration: number;
}

/** The modes a client may ask for (joinOrCreate, createMatch). */
export function listModes(base: string, options: LobbyOptions = {}): Promise<ModeInfo[]> {
  return request<ModeInfo[]>(base, '/modes', options);
}

/** The open matches the server lists (private ones are not). */
export function listMatches(base: string, options: LobbyOptions = {}): Promise<MatchInfo[]> {
  return request<MatchInfo[]>(base, '/matches', options);
}

/** One match by id (a private one too). */
export function getMatch(base: string, id: string, options: LobbyOptions = {}): Promise<MatchInfo> {
  return request<MatchInfo>(base, `/matches/${encodeURIComponent(id)}`, options);
}

/** Creates a match of `mode`; a private one is left out of the list and joined by its id. */
export function createMatch(base: string, mode: string, isPrivate = false, options: LobbyOptions = {}): Promise<MatchInfo> {
  return request<MatchInfo>(base, '/matches', options, { method: 'POST', body: JSON.stringify({ mode, private: isPrivate }) });
}

/** Joins the fullest open match of `mode` with a seat, or a new one (Hello.mode). */
export function joinOrCreate(url: string, name: string, mode: string, token = '', options: ConnectOptions = {}): Promise<ArenaClient> {
  return connect(url, name, token, { ...options, mode, match: undefined });
}

/** Joins the match `matchId` (Hello.match). */
export function join(url: string, name: string, matchId: string, token = '', options: ConnectOptions = {}): Promise<ArenaClient> {
  return connect(url, name, token, { ...options, match: matchId, mode: undefined });
}

/** Creates a match of `mode` through the lobby at `base`, then joins it over `url`. */
export async function create(
  base: string,
  url: string,
  name: string,
  mode: string,
  token = '',
  options: ConnectOptions & { private?: boolean; lobby?: LobbyOptions } = {},
): Promise<ArenaClient> {
  const made = await createMatch(base, mode, options.private ?? false, { token, ...options.lobby });
  return join(url, name, made.id, token, options);
}
