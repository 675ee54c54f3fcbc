// The seed's report (its Appendix A table) for a run, per robot or for the room: the figures
// as a table, three plots (the rates, the response-time histogram, response time over the
// run) and the whole as CSV. Read through ListRuns and GetReport; when the database cannot be
// read, it says so and the rest of the page goes on.

const kFigures = [
  ["transmissions_sent", "Transmissions sent"], ["frame_attempts", "Frame attempts"],
  ["transmissions_received", "Transmissions received"], ["successfully_matched", "Successfully matched"],
  ["dropped", "Dropped"], ["false_positives", "False positives"], ["false_positive_rate_pct", "False positive rate %"],
  ["duplicates", "Duplicates"], ["successful_transmissions", "Successful transmissions"],
  ["success_rate_pct", "Success rate %"], ["sender_confirmed", "Sender confirmed"],
  ["sender_confirmed_rate_pct", "Sender confirmed rate %"], ["crc_accepted", "CRC accepted"],
  ["crc_rejected", "CRC rejected"], ["negative_confirmations_sent", "NACKs sent"],
  ["error_catch_rate_pct", "Error catch rate %"], ["response_time_avg_ms", "Response time avg ms"],
  ["response_time_min_ms", "Response time min ms"], ["response_time_max_ms", "Response time max ms"],
  ["latency_avg_ms", "Latency avg ms"], ["refused", "Refused"], ["refused_authentication", "Refused (authentication)"],
  ["every_robot_stops_sent", "Stops for every robot sent"], ["renewals_sent", "Renewals sent"],
  ["air_waits", "Waits for the air"],
];
const kRates = [["success_rate_pct", "success"], ["sender_confirmed_rate_pct", "confirmed"],
  ["error_catch_rate_pct", "errors caught"], ["false_positive_rate_pct", "false positives"]];
const kBinMs = 10;

function csvField(v) {
  const s = v === undefined || v === null ? "" : String(v);
  return /[",\n\r]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

export function reportCsv(report) {
  const lines = ["figure,value", ...kFigures.map(([k, name]) => `${csvField(name)},${csvField(report[k])}`), "",
    "command_id,command,position,attempt,frame_bits,chord_started_unix_ms,answer,response_time_ms,latency_ms"];
  for (const f of report.frames || [])
    lines.push([f.command_id, f.command, f.position, f.attempt, f.frame_bits, f.chord_started_unix_ms, f.answer,
      f.response_time_ms, f.latency_ms].map(csvField).join(","));
  return lines.join("\r\n") + "\r\n";
}

function bars() { return uPlot.paths.bars({ size: [0.7, 60] }); }

export class Report {
  constructor(socket, e) {
    this.socket = socket;
    this.e = e;
    this.report = null;
    this.plots = [];
  }

  async refreshRuns() {
    try {
      const { runs = [] } = await this.socket.unary("ListRuns", { limit: 50 });
      const chosen = this.e.runPicker.value;
      this.e.runPicker.replaceChildren(...runs.slice().sort((a, b) => Number(b.number) - Number(a.number)).map((r) => {
        const o = document.createElement("option");
        o.value = r.run_id;
        o.textContent = `#${r.number} ${r.label} (${r.profile}, ${r.transmissions_sent} sent)`;
        return o;
      }));
      if (chosen) this.e.runPicker.value = chosen;
      if (!runs.length) return this.say("No runs yet: the report is per run. Start one with Test sequence.");
      await this.load();
    } catch (error) {
      this.say(`The runs cannot be read now: ${error.message}`);
    }
  }

  say(text) { this.e.message.textContent = text; }

  async load() {
    const request = { include_frames: true, robot: this.e.robotPicker.value };
    if (this.e.runPicker.value) request.run_id = this.e.runPicker.value;
    try {
      this.report = await this.socket.unary("GetReport", request);
      this.say("");
      this.draw();
    } catch (error) {
      this.say(`The report cannot be read now: ${error.message}`);
    }
  }

  draw() {
    const r = this.report;
    const rows = kFigures.map(([k, name]) => {
      const tr = document.createElement("tr");
      const v = r[k];
      tr.innerHTML = "<th></th><td></td>";
      tr.firstChild.textContent = name;
      tr.lastChild.textContent = v === undefined ? "N/A" : typeof v === "number" && !Number.isInteger(v) ? v.toFixed(1) : v;
      return tr;
    });
    this.e.table.replaceChildren(...rows);
    this.plots.forEach((p) => p.destroy());
    const rates = kRates.map(([k]) => r[k] ?? 0);
    const times = (r.frames || []).filter((f) => f.response_time_ms !== undefined);
    const top = Math.max(kBinMs, ...times.map((f) => f.response_time_ms));
    const bins = Array.from({ length: Math.ceil(top / kBinMs) + 1 }, (_, i) => i * kBinMs);
    const counts = bins.map(() => 0);
    for (const f of times) counts[Math.floor(f.response_time_ms / kBinMs)]++;
    const size = { width: 380, height: 200 };
    this.plots = [
      new uPlot({ ...size, title: "", scales: { x: { time: false }, y: { range: [0, 100] } },
        axes: [{ values: (u, ticks) => ticks.map((t) => kRates[t]?.[1] ?? "") }, {}],
        series: [{}, { label: "%", fill: "#39f8", stroke: "#39f", paths: bars(), points: { show: false } }] },
      [kRates.map((_, i) => i), rates], this.e.rates),
      new uPlot({ ...size, scales: { x: { time: false } },
        series: [{ label: "ms" }, { label: "frames", fill: "#3c38", stroke: "#3c3", paths: bars(), points: { show: false } }] },
      [bins, counts], this.e.histogram),
      new uPlot({ ...size, scales: { x: { time: true } },
        series: [{}, { label: "ms", stroke: "#f80", width: 0, points: { show: true, size: 4 } }] },
      [times.map((f) => Number(f.chord_started_unix_ms) / 1000), times.map((f) => f.response_time_ms)], this.e.overRun),
    ];
  }

  downloadCsv() {
    if (!this.report) return this.say("No report to download yet.");
    const blob = new Blob([reportCsv(this.report)], { type: "text/csv" });
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = `dtmf-report-run-${this.report.run?.number ?? "latest"}${this.e.robotPicker.value ? `-${this.e.robotPicker.value}` : ""}.csv`;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
    window.dtmfLastCsv = reportCsv(this.report);  // for the page's tests: the very bytes downloaded
  }
}
