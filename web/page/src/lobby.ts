// The lobby view (?lobby): the server's listed matches (GET /matches, through the SDK),
// refreshed every REFRESH_MS, each with a link to join it and one to watch it, and a form
// that creates a match (POST /matches) and then goes into it. A failed request shows as one
// line of text; the state is in window.arenaPage.lobby for tests and the console.
import { createMatch, listMatches } from './arena-sdk.mjs';
import type { LobbyOptions, MatchInfo } from './arena-sdk.mjs';
import { PageQuery, inviteLink, joinLink, watchLink } from './links.js';

const REFRESH_MS = 2000;

export interface LobbyState {
  /** The matches of the last list received (private ones are never listed). */
  matches: MatchInfo[];
  /** The line shown: the last create's failure, else the last refresh's; null when neither failed. */
  error: string | null;
  /** Lists received. */
  refreshes: number;
  /** The match the form created, and for a private one its invitation (an absolute link). */
  created: MatchInfo | null;
  invitation: string | null;
}

export function newLobbyState(): LobbyState {
  return { matches: [], error: null, refreshes: 0, created: null, invitation: null };
}

function el<T extends HTMLElement>(id: string): T {
  const e = document.getElementById(id);
  if (!e) throw new Error(`the page has no #${id}`);
  return e as T;
}

function reason(e: unknown): string {
  const message = e instanceof Error ? e.message : String(e);
  // fetch's own failure says nothing of where it went.
  return e instanceof TypeError ? `cannot reach the lobby: ${message}` : message;
}

/** "20:41:07" in the browser's time zone; the created field is UTC and may be '' (unknown). */
function timeOfDay(created: string): string {
  const at = new Date(created);
  return created === '' || Number.isNaN(at.getTime()) ? '–' : at.toLocaleTimeString();
}

function link(text: string, href: string): HTMLAnchorElement {
  const a = document.createElement('a');
  a.textContent = text;
  a.href = href;
  a.className = text;
  return a;
}

class LobbyView {
  private readonly rows = el('matches');
  private readonly empty = el('no-matches');
  private readonly modesSeen = el('modes-seen');
  private readonly errorLine = el('lobby-error');
  private readonly invitation = el('invitation');
  private readonly invitationLink = el<HTMLAnchorElement>('invitation-link');
  private readonly nameInput = el<HTMLInputElement>('lobby-name');

  constructor(private readonly state: LobbyState, private readonly token: string) {}

  name(): string {
    return this.nameInput.value.trim() || 'player';
  }

  /** One row a match: what it is, and the links into it as far as it has room. */
  showMatches(): void {
    const rows = this.state.matches.map((m) => {
      const tr = document.createElement('tr');
      tr.dataset.match = m.id;
      const cells = [m.id, m.mode, `${m.players}/${m.capacity}`, String(m.spectators), m.state, timeOfDay(m.created)];
      for (const text of cells) {
        const td = document.createElement('td');
        td.textContent = text;
        tr.appendChild(td);
      }
      tr.cells[5].title = m.created;
      const links = document.createElement('td');
      if (m.state === 'open') links.append(link('join', joinLink(m.id, this.name(), this.token)), ' ');
      if (m.state !== 'ending') links.append(link('watch', watchLink(m.id, this.token)));
      tr.appendChild(links);
      return tr;
    });
    this.rows.replaceChildren(...rows);
    this.empty.hidden = rows.length > 0;
    // The mode input offers the modes in the list (the server has no list of its modes).
    const modes = [...new Set(this.state.matches.map((m) => m.mode))].sort();
    this.modesSeen.replaceChildren(...modes.map((mode) => Object.assign(document.createElement('option'), { value: mode })));
  }

  showError(): void {
    this.errorLine.textContent = this.state.error ?? '';
    this.errorLine.hidden = this.state.error === null;
  }

  showInvitation(): void {
    this.invitationLink.textContent = this.state.invitation ?? '';
    this.invitationLink.href = this.state.invitation ?? '';
    this.invitation.hidden = this.state.invitation === null;
  }
}

/** Shows the lobby in place of the game and keeps it current until the page leaves. */
export function showLobby(state: LobbyState, query: PageQuery): void {
  document.body.classList.add('lobby');
  el('lobby').hidden = false;
  el<HTMLInputElement>('lobby-name').value = query.name;
  const view = new LobbyView(state, query.token);
  const base = location.origin;
  const options: LobbyOptions = query.token ? { token: query.token } : {};
  let listError: string | null = null;
  let createError: string | null = null;
  const showErrors = () => {
    state.error = createError ?? listError;
    view.showError();
  };

  const refresh = async () => {
    try {
      state.matches = await listMatches(base, options);
      ++state.refreshes;
      listError = null;
      view.showMatches();
    } catch (e) {
      listError = reason(e);
    }
    showErrors();
    // The next request only once this one is answered: a slow server gets no pile of them.
    setTimeout(refresh, REFRESH_MS);
  };
  void refresh();

  // The join links carry the name: a new name rewrites them at once.
  el('lobby-name').addEventListener('input', () => view.showMatches());

  const form = el<HTMLFormElement>('create-form');
  const submit = el<HTMLButtonElement>('create-submit');
  form.addEventListener('submit', async (event) => {
    event.preventDefault();
    const mode = el<HTMLInputElement>('create-mode').value.trim();
    const isPrivate = el<HTMLInputElement>('create-private').checked;
    submit.disabled = true;
    createError = null;
    showErrors();
    try {
      const made = await createMatch(base, mode, isPrivate, options);
      state.created = made;
      // A private match is not listed: its link is the only way in for anyone else. The game's
      // HUD shows it too, as its invite link.
      state.invitation = made.private ? inviteLink(made.id, location.href) : null;
      view.showInvitation();
      location.assign(joinLink(made.id, view.name(), query.token));
    } catch (e) {
      createError = reason(e);
      showErrors();
      submit.disabled = false;
    }
  });
}
