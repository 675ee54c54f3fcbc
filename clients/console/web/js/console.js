// The console page: connects to dtmf-console (socket.js), watches the air (spectrogram.js),
// lists the robots (robots.js), drives (drive.js) and reports (report.js). Everything it shows
// or does is a call of the public API. When the server or the console goes away it says so,
// keeps what it showed, and starts again by itself when they are back.
import { ConsoleSocket } from "./socket.js";
import { Spectrogram } from "./spectrogram.js";
import { Robots } from "./robots.js";
import { Driving } from "./drive.js";
import { Report } from "./report.js";

const $ = (id) => document.getElementById(id);
const kWatch = { spectrum: true, columns_per_s: 25, bins: 160 };
const kRetryWatchMs = 2000;
const kRobotsEveryMs = 5000;

function pageToken() {
  const inPage = document.querySelector('meta[name="dtmf-page-token"]').content;
  if (inPage) return inPage;
  // Off loopback the operator's token guards the console; the page does not carry it.
  let token = sessionStorage.getItem("dtmf-operator-token");
  if (!token) {
    token = prompt("This console asks for the operator's token (dtmf-console --auth-token-file):") || "";
    sessionStorage.setItem("dtmf-operator-token", token);
  }
  return token;
}

const socket = new ConsoleSocket(pageToken());
const spectrogram = new Spectrogram($("spectrogram"), $("marks"), $("air-log"));
const robots = new Robots($("robot-cards"), socket);
let robotList = [];
const picked = () => robotList.find((r) => r.name === $("robot-picker").value) || null;
const driving = new Driving(socket, {
  commands: $("commands"), teleopButton: $("teleop-button"), teleopMessage: $("teleop-message"),
  teleopTarget: $("teleop-target"), teleopConfirmed: $("teleop-confirmed"), teleopLease: $("teleop-lease"),
  teleopQuality: $("teleop-quality"),
}, picked);
const report = new Report(socket, {
  runPicker: $("run-picker"), robotPicker: $("report-robot"), message: $("report-message"), table: $("report-table"),
  rates: $("plot-rates"), histogram: $("plot-histogram"), overRun: $("plot-over-run"),
});
window.dtmfConsole = { socket, spectrogram, robots, driving, report };

function showState(state, text) {
  const badge = $("connection");
  badge.dataset.state = state;
  badge.textContent = text;
}

let watching = null;
function watchAir() {
  if (watching) return;
  watching = socket.call("WatchAir", kWatch, (m) => {
    if (m.spectrum) spectrogram.column(m);
    else { spectrogram.event(m); robots.watched(m); }
    if (Number(m.dropped_columns) || Number(m.dropped_events))
      $("dropped").textContent = `lost by the sender for this page: ${m.dropped_columns} columns, ${m.dropped_events} events`;
  });
  showState("connected", `live: dtmf-server ${socket.server || ""}`);
  watching.done.then((status) => {
    watching = null;
    if (socket.state !== "connected") return;  // the socket's own state says more
    showState("server-down", `dtmf-server does not answer (${status.name}: ${status.message}); trying again`);
    setTimeout(watchAir, kRetryWatchMs);
  });
}

async function listRobots() {
  try {
    const { robots: list = [] } = await socket.unary("ListRobots", {});
    robotList = list;
    robots.set(list);
    for (const picker of [$("robot-picker"), $("report-robot")]) {
      for (const r of list) {
        if ([...picker.options].some((o) => o.value === r.name)) continue;
        const o = document.createElement("option");
        o.value = r.name;
        o.textContent = r.name;
        picker.append(o);
      }
    }
    $("drive-robot").textContent = picked() ? `→ ${picked().name}` : "";
  } catch (error) {
    // The air watch says when the server is away; nothing more to say here.
  }
}

socket.on("state", (state, detail) => {
  if (state === "connected") {
    socket.server = detail.server;
    watchAir();
    listRobots();
    robots.followReceptions();
    report.refreshRuns();
  } else if (state === "console-down") {
    showState(state, detail);
  }
});
socket.on("dropped", (n) => { $("dropped").textContent = `lost on the way to this page: ${n} columns`; });
setInterval(() => { if (socket.state === "connected") listRobots(); }, kRobotsEveryMs);

$("drive-form").addEventListener("submit", (e) => { e.preventDefault(); driving.drive(e.target); });
$("turn-form").addEventListener("submit", (e) => { e.preventDefault(); driving.turn(e.target); });
$("stop-button").addEventListener("click", () => driving.stop());
$("reset-button").addEventListener("click", () => driving.reset());
$("sequence-button").addEventListener("click", () => driving.sequence($("sequence-label").value));
$("stop-every-robot").addEventListener("click", () => driving.stopEveryRobot());
$("teleop-button").addEventListener("click", (e) => { e.target.blur(); driving.toggleTeleop(); });
$("robot-picker").addEventListener("change", () => { $("drive-robot").textContent = picked() ? `→ ${picked().name}` : ""; });
$("run-picker").addEventListener("change", () => report.load());
$("report-robot").addEventListener("change", () => report.load());
$("report-refresh").addEventListener("click", () => report.refreshRuns());
$("report-csv").addEventListener("click", () => report.downloadCsv());

document.addEventListener("keydown", (e) => {
  if (e.target.closest("input, select, textarea") || e.ctrlKey || e.metaKey || e.altKey) return;
  if (e.key === "e") { driving.stopEveryRobot(); e.preventDefault(); return; }
  if (driving.key(e.key)) e.preventDefault();
});
