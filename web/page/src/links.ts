// The page's URL parameters, and the links between the lobby and the game made from them.
// Every link is the page's own address with another query: relative ("?match=ID&name=you"),
// so that it works whatever path serves the page, except the invitation, which is sent to
// someone else and so is absolute.

/** What the page's address asks for. */
export interface PageQuery {
  /** ?lobby: the list of matches and the create form instead of the game. */
  lobby: boolean;
  /** ?spectate: watch without a ship. */
  spectate: boolean;
  /** ?name= trimmed; '' when absent. */
  name: string;
  /** ?token=: a join token for a server run with --token-secret; '' when absent. */
  token: string;
  /** ?match=ID: join that match (Hello.match); '' when absent. */
  match: string;
  /** ?mode=NAME: join or create a match of that mode (Hello.mode); '' when absent. */
  mode: string;
  /** ?debug=lag (a comma-separated list): draws the targets of the player's last shots as the
   *  view each shot's input carried, the world the server rewinds to judge it. */
  debugLag: boolean;
}

export function readQuery(search: string): PageQuery {
  const params = new URLSearchParams(search);
  const text = (key: string) => (params.get(key) ?? '').trim();
  return {
    lobby: params.has('lobby'),
    spectate: params.has('spectate'),
    name: text('name'),
    token: text('token'),
    match: text('match'),
    mode: text('mode'),
    debugLag: params.getAll('debug').some((v) => v.split(',').map((w) => w.trim()).includes('lag')),
  };
}

// A flag (true) is written bare, as "?spectate", not "?spectate=". Empty values are left out.
type QueryPart = [key: string, value: string | true];

function query(parts: QueryPart[]): string {
  const written = parts
    .filter(([, value]) => value !== '')
    .map(([key, value]) => (value === true ? key : `${key}=${encodeURIComponent(value)}`));
  return `?${written.join('&')}`;
}

/** Plays the match `match` as `name`. The token goes along: it is the player's own. */
export function joinLink(match: string, name: string, token: string): string {
  return query([['match', match], ['name', name], ['token', token]]);
}

/** Watches the match `match` (a spectator's seat). */
export function watchLink(match: string, token: string): string {
  return query([['match', match], ['spectate', true], ['token', token]]);
}

/** Back to the lobby, keeping the name and the token. */
export function lobbyLink(name: string, token: string): string {
  return query([['lobby', true], ['name', name], ['token', token]]);
}

/** The absolute address that brings someone else into the match `match`: no name (theirs is
 *  theirs to choose) and never the token (it is this player's). */
export function inviteLink(match: string, pageHref: string): string {
  return new URL(query([['match', match]]), pageHref).href;
}
