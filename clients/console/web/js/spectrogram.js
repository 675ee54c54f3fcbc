// The scrolling spectrogram of what the sender's microphone hears, with each frame sent, each
// answer and the air heard busy marked at its audio time. Columns are drawn as they come (the
// canvas moves left by a column's width); the marks are redrawn over them on the next
// animation frame, placed by audio time against the newest column's. What was drawn, and how
// late, is kept in `stats` (the console's bench and tests read it).

const kShownMs = 12000;        // the width of the picture, in audio time
const kFloorDbfs = -110;       // drawn black
const kTopDbfs = -20;          // drawn white
const kKeptStats = 2000;
const kLabelRows = 2;          // rows of frame labels above the picture, and of answer labels below
const kLabelRowPx = 12;        // one row's height (11 px text)

// A dark-to-bright palette (black, blue, magenta, orange, white) as 256 RGB entries.
// Draws a label in the first of `rows` (each the x where its last label ended) where it
// overlaps none drawn before it; with no room in any, leaves it out: the log under the picture
// names every frame and answer, and labels written over each other name none.
function placeLabel(ctx, rows, text, x, y, rowStepPx) {
  const row = rows.findIndex((end) => x >= end);
  if (row < 0) return;
  ctx.fillText(text, x, y + row * rowStepPx);
  rows[row] = x + ctx.measureText(text).width + 6;
}

function palette() {
  const stops = [[0, 0, 0], [20, 30, 120], [150, 40, 150], [250, 140, 30], [255, 255, 230]];
  const lut = new Uint8ClampedArray(256 * 3);
  for (let i = 0; i < 256; i++) {
    const x = (i / 255) * (stops.length - 1);
    const k = Math.min(Math.floor(x), stops.length - 2);
    const f = x - k;
    for (let c = 0; c < 3; c++) lut[i * 3 + c] = stops[k][c] * (1 - f) + stops[k + 1][c] * f;
  }
  return lut;
}

export class Spectrogram {
  constructor(canvas, marksCanvas, log) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.marks = marksCanvas.getContext("2d");
    this.log = log;
    this.lut = palette();
    this.latestMs = null;        // audio time of the newest column
    this.columnMs = 40;          // audio time between columns (from their times)
    this.band = null;            // {low_hz, step_hz, bins}
    this.frames = [];            // {ms, chordMs, label, authenticated}
    this.answers = [];           // {ms, answer, label}
    this.busy = [];              // {fromMs, toMs|null}
    this.stats = { columns: 0, columnDelaysMs: [], markDelaysMs: [], framesMarked: 0, answersMarked: 0 };
    this.ctx.fillStyle = "#000";
    this.ctx.fillRect(0, 0, canvas.width, canvas.height);
    this.redrawPending = false;
  }

  pxPerMs() { return this.canvas.width / kShownMs; }
  xOf(ms) { return this.canvas.width - (this.latestMs - ms) * this.pxPerMs(); }

  // A WatchAirResponse carrying a spectrum column.
  column(watch) {
    const c = watch.spectrum;
    const ms = Number(watch.audio_ms);
    if (this.latestMs !== null && ms > this.latestMs) this.columnMs = 0.8 * this.columnMs + 0.2 * (ms - this.latestMs);
    const step = this.latestMs === null ? 0 : Math.max(0, ms - this.latestMs) * this.pxPerMs();
    this.latestMs = ms;
    this.band = { low_hz: c.low_hz, step_hz: c.step_hz, bins: c.level_dbfs.length };
    const { width, height } = this.canvas;
    if (step > 0) this.ctx.drawImage(this.canvas, -step, 0);  // the picture moves left
    const w = Math.max(1, Math.ceil(step || this.columnMs * this.pxPerMs()));
    const image = this.ctx.createImageData(w, height);
    const levels = c.level_dbfs;
    for (let y = 0; y < height; y++) {
      const bin = Math.floor(((height - 1 - y) / height) * levels.length);
      const v = Math.round(((levels[bin] - kFloorDbfs) / (kTopDbfs - kFloorDbfs)) * 255);
      const i = Math.max(0, Math.min(255, v)) * 3;
      for (let x = 0; x < w; x++) {
        const o = (y * w + x) * 4;
        image.data[o] = this.lut[i];
        image.data[o + 1] = this.lut[i + 1];
        image.data[o + 2] = this.lut[i + 2];
        image.data[o + 3] = 255;
      }
    }
    this.ctx.putImageData(image, width - w, 0);
    this.keep(this.stats.columnDelaysMs, Date.now() - Number(watch.time_unix_ms));
    this.stats.columns++;
    this.scheduleMarks();
  }

  // Any other WatchAirResponse: a frame, an answer, the air busy or quiet.
  event(watch) {
    const ms = Number(watch.audio_ms);
    if (watch.frame_played) {
      const f = watch.frame_played;
      const who = f.robots.length ? f.robots.join("+") : "every robot";
      const number = f.sequence !== undefined ? ` seq ${f.sequence}` : f.counter !== undefined ? ` #${f.counter}` : "";
      const retry = f.attempt > 1 ? ` (attempt ${f.attempt})` : "";
      const label = `${who} ${f.kind}${number}${f.authenticated ? " (auth)" : ""}${retry}`;
      this.frames.push({ ms, chordMs: f.chord_ms, label, authenticated: f.authenticated });
      this.stats.framesMarked++;
      this.note("frame", `${label}: ${f.command}`, watch);
    } else if (watch.frame_answered) {
      const a = watch.frame_answered;
      const rt = a.response_time_ms !== undefined ? ` after ${Math.round(a.response_time_ms)} ms` : "";
      const label = `${a.robot} ${a.answer.toUpperCase()}${a.authenticated ? " (auth)" : ""}`;
      this.answers.push({ ms, answer: a.answer, label });
      this.stats.answersMarked++;
      this.keep(this.stats.markDelaysMs, Date.now() - Number(watch.time_unix_ms));
      this.note(a.answer, `${label}${rt} (frame ${a.frame_index + 1}, attempt ${a.attempt})`, watch);
    } else if (watch.air_busy) {
      const b = watch.air_busy;
      if (b.busy) this.busy.push({ fromMs: ms, toMs: null });
      else if (this.busy.length && this.busy.at(-1).toMs === null) this.busy.at(-1).toMs = ms;
      this.note("busy", b.busy ? `air busy: ${b.level_dbfs.toFixed(0)} dBFS over a floor of ${b.floor_dbfs.toFixed(0)}`
        : "air quiet again", watch);
    }
    this.scheduleMarks();
  }

  keep(list, value) {
    list.push(value);
    if (list.length > kKeptStats) list.shift();
  }

  note(kind, text, watch) {
    const li = document.createElement("li");
    li.dataset.kind = kind;
    li.textContent = `${new Date(Number(watch.time_unix_ms)).toLocaleTimeString()} ${text}`;
    this.log.prepend(li);
    while (this.log.children.length > 200) this.log.lastChild.remove();
  }

  scheduleMarks() {
    if (this.redrawPending) return;
    this.redrawPending = true;
    requestAnimationFrame(() => { this.redrawPending = false; this.drawMarks(); });
  }

  drawMarks() {
    const ctx = this.marks;
    const { width, height } = ctx.canvas;
    ctx.clearRect(0, 0, width, height);
    if (this.latestMs === null) return;
    const oldest = this.latestMs - kShownMs;
    this.frames = this.frames.filter((f) => f.ms + f.chordMs >= oldest);
    this.answers = this.answers.filter((a) => a.ms >= oldest);
    this.busy = this.busy.filter((b) => b.toMs === null || b.toMs >= oldest);
    ctx.font = "11px sans-serif";
    for (const b of this.busy) {
      const x0 = this.xOf(b.fromMs);
      const x1 = b.toMs === null ? width : this.xOf(b.toMs);
      ctx.fillStyle = "rgba(255, 200, 0, 0.8)";
      ctx.fillRect(x0, height - 5, Math.max(2, x1 - x0), 5);
    }
    const frameRows = new Array(kLabelRows).fill(-Infinity);
    for (const f of this.frames) {
      const x0 = this.xOf(f.ms);
      const x1 = this.xOf(f.ms + f.chordMs);
      ctx.strokeStyle = f.authenticated ? "#7fffd4" : "#ffffff";
      ctx.lineWidth = 1.5;
      const top = 14 + kLabelRowPx * (kLabelRows - 1);
      ctx.strokeRect(x0, top, Math.max(2, x1 - x0), height - 10 - top);
      ctx.fillStyle = ctx.strokeStyle;
      placeLabel(ctx, frameRows, f.label, x0 + 2, 11, kLabelRowPx);
    }
    if (this.band) {  // the frequency axis, in kHz
      ctx.fillStyle = "rgba(255, 255, 255, 0.7)";
      ctx.font = "10px sans-serif";
      const top = this.band.low_hz + this.band.step_hz * this.band.bins;
      for (const khz of [2, 5, 10, 15, 20]) {
        const y = height - ((khz * 1000 - this.band.low_hz) / (top - this.band.low_hz)) * height;
        if (y > 10 && y < height) ctx.fillText(`${khz} kHz`, 2, y);
      }
    }
    const symbols = { ack: ["▲", "#3c3"], nack: ["▼", "#f44"], none: ["✕", "#aaa"] };
    const answerRows = new Array(kLabelRows).fill(-Infinity);
    for (const a of this.answers) {
      const [symbol, colour] = symbols[a.answer] || ["?", "#fff"];
      const x = this.xOf(a.ms);
      ctx.fillStyle = colour;
      ctx.font = "16px sans-serif";
      ctx.fillText(symbol, x - 6, height - 10);
      ctx.font = "11px sans-serif";
      placeLabel(ctx, answerRows, a.label, x + 8, height - 12, -kLabelRowPx);
    }
  }
}
