// Driving from the page: Drive, Turn, Stop, Reset and the seed's test sequence as buttons,
// keyboard teleop with dtmfctl teleop's keys (clients/cli/teleop_keys.h), and the stop for
// every robot. Each is a call of the public API; its progress is listed as it comes.

const kLinearStep = 0.01;   // m/s a key press, as dtmfctl teleop
const kAngularStep = 0.1;   // rad/s
const kLease_s = 0.5;
const kRepeatMs = 250;      // the target again, well within the server's one second of silence
const kLimits = { burger: [0.22, 2.84], waffle: [0.26, 1.82], waffle_pi: [0.26, 1.82] };

const eventNames = {
  FRAME_EVENT_QUEUED: "queued", FRAME_EVENT_TRANSMITTING: "on air", FRAME_EVENT_ACK: "ACK",
  FRAME_EVENT_NACK: "NACK", FRAME_EVENT_NO_ANSWER: "no answer", FRAME_EVENT_RETRANSMITTING: "sent again",
  FRAME_EVENT_AWAITING_DECISION: "awaiting a decision", FRAME_EVENT_CONFIRMED: "confirmed",
  FRAME_EVENT_CONTINUED: "continued unconfirmed", FRAME_EVENT_FAILED: "failed", FRAME_EVENT_SENT: "sent",
  FRAME_EVENT_WAITING_FOR_AIR: "waiting for the air",
};

export function describeProgress(p) {
  const name = eventNames[p.event] || p.event;
  const frame = p.frame_count > 1 ? ` frame ${p.frame_index + 1}/${p.frame_count}` : "";
  const attempt = p.attempt > 1 ? ` attempt ${p.attempt}` : "";
  const rt = p.response_time_ms ? ` ${Math.round(p.response_time_ms)} ms` : "";
  const lock = p.answer_authenticated ? " (auth)" : "";
  return `${name}${frame}${attempt}${rt}${lock}${p.detail ? `: ${p.detail}` : ""}`;
}

export class Driving {
  constructor(socket, elements, robot) {
    this.socket = socket;
    this.e = elements;
    this.robot = robot;  // () => {name, model} of the picked robot, or null for the server's only one
    this.teleop = null;
    this.target = { linear: 0, angular: 0 };
  }

  options() {
    const r = this.robot();
    return r ? { robot: r.name } : {};
  }

  // Runs a command and lists its progress; the list item says how it ended.
  command(method, request, label) {
    const li = document.createElement("li");
    const who = this.robot()?.name || "";
    li.textContent = `${label}${who ? ` → ${who}` : ""}: asked`;
    this.e.commands.prepend(li);
    while (this.e.commands.children.length > 50) this.e.commands.lastChild.remove();
    const call = this.socket.call(method, request, (m) => {
      const p = m.progress;
      const run = m.command_count ? ` [${m.command_index + 1}/${m.command_count}]` : "";
      if (p) li.textContent = `${label}${who ? ` → ${who}` : ""}${run}: ${describeProgress(p)}`;
    });
    call.done.then((s) => {
      li.dataset.outcome = s.code === 0 ? "ok" : "failed";
      if (s.code !== 0) li.textContent += ` — ${s.name}: ${s.message}`;
      else if (!/confirmed|sent|continued/.test(li.textContent)) li.textContent += " — done";
    });
    return call;
  }

  drive(form) {
    const f = new FormData(form);
    const request = { speed_percent: Number(f.get("speed_percent")), options: this.options() };
    if (f.get("duration_s") !== "") request.duration_s = Number(f.get("duration_s"));
    this.command("Drive", request, `Drive ${request.speed_percent} %`);
  }

  turn(form) {
    const f = new FormData(form);
    const request = { rotation_percent: Number(f.get("rotation_percent")), options: this.options() };
    if (f.get("duration_s") !== "") request.duration_s = Number(f.get("duration_s"));
    this.command("Turn", request, `Turn ${request.rotation_percent} %`);
  }

  stop() { this.command("Stop", { options: this.options() }, "Stop"); }
  reset() { this.command("Reset", { options: this.options() }, "Reset"); }
  sequence(label) {
    this.command("RunTestSequence", { label, options: this.options() }, `Test sequence "${label}"`);
  }
  stopEveryRobot() {
    if (this.teleop) this.endTeleop(false);
    this.command("Stop", { all_robots: true }, "STOP EVERY ROBOT");
  }

  // Keyboard teleop on or off. Off sends Stop, as dtmfctl teleop's q does.
  toggleTeleop() {
    if (this.teleop) return this.endTeleop(true);
    this.target = { linear: 0, angular: 0 };
    const first = { linear_mps: 0, angular_radps: 0, lease_s: kLease_s, options: this.options() };
    const call = this.socket.call("Teleop", first, (m) => this.teleopStatus(m));
    this.teleop = { call, repeat: setInterval(() => this.sendTarget(), kRepeatMs) };
    this.e.teleopButton.textContent = "Keyboard teleop: on";
    this.e.teleopButton.setAttribute("aria-pressed", "true");
    this.e.teleopMessage.textContent = `driving ${this.robot()?.name || "the robot"} with the keyboard`;
    call.done.then((s) => {
      if (this.teleop?.call !== call) return;
      this.endTeleop(false);
      this.e.teleopMessage.textContent = s.code === 0 ? "teleop ended" : `teleop ended — ${s.name}: ${s.message}`;
    });
  }

  endTeleop(sendStop) {
    const t = this.teleop;
    this.teleop = null;
    clearInterval(t.repeat);
    t.call.close();
    this.e.teleopButton.textContent = "Keyboard teleop: off";
    this.e.teleopButton.setAttribute("aria-pressed", "false");
    if (sendStop) this.stop();
  }

  sendTarget() {
    if (!this.teleop) return;
    this.teleop.call.send({ linear_mps: this.target.linear, angular_radps: this.target.angular, lease_s: kLease_s });
    this.e.teleopTarget.textContent =
      `${this.target.linear.toFixed(2)} m/s, ${this.target.angular.toFixed(1)} rad/s`;
  }

  // A key while teleop is on; true if it was one of teleop's.
  key(k) {
    if (!this.teleop) return false;
    const [maxLinear, maxAngular] = kLimits[this.robot()?.model] || kLimits.burger;
    const clamp = (v, m) => Math.max(-m, Math.min(m, Math.round(v * 100) / 100));
    const t = this.target;
    if (k === "w") t.linear = clamp(t.linear + kLinearStep, maxLinear);
    else if (k === "x") t.linear = clamp(t.linear - kLinearStep, maxLinear);
    else if (k === "a") t.angular = clamp(t.angular + kAngularStep, maxAngular);
    else if (k === "d") t.angular = clamp(t.angular - kAngularStep, maxAngular);
    else if (k === "s" || k === " ") { t.linear = 0; t.angular = 0; }
    else return false;
    this.sendTarget();
    return true;
  }

  teleopStatus(m) {
    if (m.confirmed)
      this.e.teleopConfirmed.textContent =
        `${m.confirmed_linear_mps.toFixed(2)} m/s, ${m.confirmed_angular_radps.toFixed(1)} rad/s (${Math.round(m.response_time_ms)} ms)`;
    this.e.teleopLease.textContent = `${m.lease_left_s.toFixed(2)} s of ${m.lease_s.toFixed(2)} s`;
    this.e.teleopQuality.textContent =
      `${Math.round(100 * m.link_quality)} % of ${m.frames_in_window} frames in ${m.link_window_s} s`;
    if (m.progress?.event === "FRAME_EVENT_FAILED") this.e.teleopMessage.textContent = describeProgress(m.progress);
  }
}
