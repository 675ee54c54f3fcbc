// The page's one socket to dtmf-console, and calls of dtmf.v1.TeleopService over it
// (clients/console/page_session.h has the messages). It reconnects by itself, waiting a
// little longer each time (to 5 s); a call open when the socket dropped ends with
// UNAVAILABLE, and whoever made it decides whether to call again (the air watch does).
// A console that restarted has a new page token: a handshake refused sends the page to read
// it from the console's page again (same origin: no other site can).

const kRetryMs = [250, 500, 1000, 2000, 5000];

export class ConsoleSocket {
  constructor(token) {
    this.token = token;
    this.calls = new Map();
    this.nextId = 1;
    this.attempt = 0;
    this.listeners = { state: [], dropped: [] };
    this.state = "connecting";
    this.open();
  }

  on(what, listener) { this.listeners[what].push(listener); }

  setState(state, detail) {
    this.state = state;
    for (const l of this.listeners.state) l(state, detail);
  }

  open() {
    const scheme = location.protocol === "https:" ? "wss:" : "ws:";
    const url = `${scheme}//${location.host}/socket?token=${encodeURIComponent(this.token)}`;
    this.ws = new WebSocket(url);
    let opened = false;
    this.ws.onopen = () => { this.attempt = 0; opened = true; };
    this.ws.onmessage = (e) => this.hear(JSON.parse(e.data));
    this.ws.onclose = () => this.closed(opened);
  }

  async freshToken() {
    try {
      const page = await (await fetch("/", { cache: "no-store" })).text();
      const found = /name="dtmf-page-token" content="([0-9a-f]{64})"/.exec(page);
      if (found) this.token = found[1];
    } catch (error) {
      // The console is away: the next attempt tries again.
    }
  }

  async closed(opened) {
    for (const [, call] of this.calls) call.end({ code: 14, name: "UNAVAILABLE", message: "the console went away" });
    this.calls.clear();
    const wait = kRetryMs[Math.min(this.attempt++, kRetryMs.length - 1)];
    this.setState("console-down", `the console does not answer; trying again in ${wait / 1000} s`);
    if (!opened && document.querySelector('meta[name="dtmf-page-token"]').content) await this.freshToken();
    setTimeout(() => this.open(), wait);
  }

  hear(message) {
    if (message.hello) return this.setState("connected", message.hello);
    if (message.dropped_columns) return this.listeners.dropped.forEach((l) => l(message.dropped_columns));
    if (message.error) return console.warn("console:", message.error);
    const call = this.calls.get(message.call);
    if (!call) return;
    if (message.message) call.onMessage(message.message);
    if (message.status) {
      this.calls.delete(message.call);
      call.end(message.status);
    }
  }

  // Opens a call: `onMessage` hears each message; the returned call's `done` resolves with
  // the status ({code, name, message}), whatever it is.
  call(method, request, onMessage = () => {}) {
    const id = this.nextId++;
    let end;
    const done = new Promise((resolve) => { end = resolve; });
    const call = {
      id, onMessage, end, done,
      send: (r) => this.post({ send: id, request: r }),
      close: () => this.post({ close: id }),
      cancel: () => this.post({ cancel: id }),
    };
    if (!this.ws || this.ws.readyState !== WebSocket.OPEN) {
      end({ code: 14, name: "UNAVAILABLE", message: "not connected to the console" });
      return call;
    }
    this.calls.set(id, call);
    this.post({ open: id, method, request });
    return call;
  }

  // A unary call's one message, or an Error carrying its status.
  async unary(method, request) {
    let reply = null;
    const call = this.call(method, request, (m) => { reply = m; });
    const status = await call.done;
    if (status.code !== 0) throw Object.assign(new Error(status.message || status.name), { status });
    return reply;
  }

  post(message) {
    if (this.ws && this.ws.readyState === WebSocket.OPEN) this.ws.send(JSON.stringify(message));
  }
}
