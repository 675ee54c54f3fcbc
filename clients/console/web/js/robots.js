// One card per robot: when it last answered, its link over the last minute (answers heard per
// frame sent, response times, as a plot), and what it heard and did (from the database:
// executed, refused and why, heard twice). Fed by the air watch and by ListReceptions.

const kWindowMs = 60000;
const kReceptionsShown = 8;

function ago(ms) {
  if (!ms) return "not since the server started";
  const s = (Date.now() - ms) / 1000;
  return s < 1 ? "just now" : s < 120 ? `${s.toFixed(1)} s ago` : `${Math.round(s / 60)} min ago`;
}

function median(values) {
  if (!values.length) return null;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
}

class RobotCard {
  constructor(robot, parent) {
    this.robot = robot;
    this.answers = [];     // {t, answer, rt}
    this.receptions = [];  // newest first
    this.commands = [];    // commands ended, newest first: {at, text, outcome}
    this.onAir = "";       // the newest frame played for it
    this.counts = { command: 0, refused: 0, repeat: 0 };
    this.element = document.createElement("article");
    this.element.className = "robot";
    this.element.dataset.robot = robot.name;
    this.element.innerHTML = `<h3></h3><dl>
      <dt>last answered</dt><dd class="last"></dd>
      <dt>link, last minute</dt><dd class="quality"></dd>
      <dt>response time</dt><dd class="response"></dd>
      <dt>heard and did</dt><dd class="did"></dd>
      <dt>on the air</dt><dd class="now"></dd></dl>
      <div class="plot"></div>
      <ol class="commands log" aria-label="its commands"></ol>
      <ol class="receptions log" aria-label="what it heard and did"></ol>`;
    this.element.querySelector("h3").textContent =
      `${robot.name} (address ${robot.address}, ${robot.model}${robot.key_id ? ", keyed" : ""})`;
    parent.append(this.element);
    // The last minute, whatever it holds: left to itself, uPlot spreads one point over years.
    this.plot = new uPlot({
      width: 300, height: 110, legend: { show: false }, cursor: { show: false },
      scales: {
        x: { time: true, range: () => { const now = Date.now() / 1000; return [now - kWindowMs / 1000, now]; } },
        y: { range: (u, min, max) => [0, Math.max(100, Math.ceil(((max ?? 0) * 1.2) / 100) * 100)] },
      },
      series: [{}, { label: "response time, ms", stroke: "#39f", points: { show: true, size: 4 }, width: 0 }],
      axes: [{ size: 30 }, { size: 40 }],
    }, [[], []], this.element.querySelector(".plot"));
  }

  answered(watch) {
    const a = watch.frame_answered;
    this.answers.push({ t: Number(watch.time_unix_ms), answer: a.answer, rt: a.response_time_ms });
    if (a.answer !== "none") this.robot.last_answered_unix_ms = Number(watch.time_unix_ms);
  }

  played(watch) {
    const f = watch.frame_played;
    const part = f.frame_count > 1 ? ` frame ${f.frame_index + 1}/${f.frame_count}` : "";
    this.onAir = `${f.command}${part}${f.attempt > 1 ? ` attempt ${f.attempt}` : ""}`;
  }

  ended(watch) {
    const c = watch.command_ended;
    this.onAir = "";
    if (/renewal/.test(c.command)) return;  // a lease kept: several a second while driving live
    this.commands.unshift({ at: Number(watch.time_unix_ms), text: `${c.command}: ${c.outcome}${c.detail ? ` (${c.detail})` : ""}`,
      outcome: c.outcome });
    this.commands.length = Math.min(this.commands.length, 20);
  }

  received(reception) {
    this.receptions.unshift(reception);
    this.receptions.length = Math.min(this.receptions.length, 100);
    if (reception.event in this.counts) this.counts[reception.event]++;
  }

  draw() {
    const now = Date.now();
    this.answers = this.answers.filter((a) => now - a.t <= kWindowMs);
    const heard = this.answers.filter((a) => a.answer !== "none");
    const q = this.element.querySelector(".quality");
    q.textContent = this.answers.length
      ? `${Math.round((100 * heard.length) / this.answers.length)} % of ${this.answers.length} ` +
        `frame${this.answers.length === 1 ? "" : "s"} answered` : "no frames";
    const times = heard.filter((a) => a.rt !== undefined).map((a) => a.rt);
    const m = median(times);
    this.element.querySelector(".response").textContent = m === null ? "–" : `median ${Math.round(m)} ms`;
    this.element.querySelector(".last").textContent = ago(this.robot.last_answered_unix_ms);
    const c = this.counts;
    this.element.querySelector(".did").textContent =
      `${c.command} executed, ${c.refused} refused, ${c.repeat} heard twice`;
    this.element.querySelector(".now").textContent = this.onAir || "nothing";
    this.element.querySelector(".commands").replaceChildren(...this.commands.slice(0, 5).map((c) => {
      const li = document.createElement("li");
      li.dataset.outcome = c.outcome === "confirmed" || c.outcome === "sent" ? "ok" : c.outcome === "failed" ? "failed" : "";
      li.textContent = `${new Date(c.at).toLocaleTimeString()} ${c.text}`;
      return li;
    }));
    const list = this.element.querySelector(".receptions");
    list.replaceChildren(...this.receptions.slice(0, kReceptionsShown).map((r) => {
      const li = document.createElement("li");
      li.dataset.event = r.event;
      const why = r.reason ? ` (${r.reason})` : "";
      const what = r.command ? `: ${r.command}` : "";
      li.textContent = `${new Date(Number(r.heard_unix_ms)).toLocaleTimeString()} ${r.event}${why}${what}` +
        `${r.authenticated ? " (auth)" : ""}${r.reply ? `, answered ${r.reply}` : ""}`;
      return li;
    }));
    const points = heard.filter((a) => a.rt !== undefined);
    this.plot.setData([points.map((a) => a.t / 1000), points.map((a) => a.rt)]);
  }
}

export class Robots {
  constructor(parent, socket) {
    this.parent = parent;
    this.socket = socket;
    this.cards = new Map();
    this.seen = new Set();  // receptions already counted (a follow that starts again lists some again)
    this.message = document.createElement("p");
    this.message.className = "message";
    parent.before(this.message);
    setInterval(() => this.cards.forEach((card) => card.draw()), 1000);
  }

  // ListRobots' answer: cards for new robots, fresh times for known ones.
  set(robots) {
    for (const robot of robots) {
      const card = this.cards.get(robot.name);
      if (card) card.robot.last_answered_unix_ms = Math.max(card.robot.last_answered_unix_ms, Number(robot.last_answered_unix_ms));
      else this.cards.set(robot.name, new RobotCard({ ...robot, last_answered_unix_ms: Number(robot.last_answered_unix_ms) }, this.parent));
    }
  }

  watched(watch) {
    if (watch.frame_answered) this.cards.get(watch.frame_answered.robot)?.answered(watch);
    if (watch.frame_played) for (const r of watch.frame_played.robots) this.cards.get(r)?.played(watch);
    if (watch.command_ended) {
      const c = watch.command_ended;
      const cards = c.robot ? [this.cards.get(c.robot)] : [...this.cards.values()];  // none named: every robot
      for (const card of cards) card?.ended(watch);
    }
  }

  // Follows every robot's receptions from the database; says so when they cannot be read, and
  // tries again.
  followReceptions() {
    const call = this.socket.call("ListReceptions", { limit: 50, follow: true }, (m) => {
      this.message.textContent = "";
      const r = m.reception;
      if (this.seen.has(r.id)) return;
      this.seen.add(r.id);
      this.cards.get(r.robot)?.received(r);
    });
    call.done.then((status) => {
      this.message.textContent = `What the robots heard cannot be read now: ${status.message || status.name}. Trying again.`;
      setTimeout(() => this.followReceptions(), 3000);
    });
  }
}
