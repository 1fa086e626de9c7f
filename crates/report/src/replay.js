"use strict";
// Mason replay: plays the embedded mission or crew plan. Exposes its state on <body>:
// data-t (the shown time), data-frames (frames drawn), data-errors (errors caught),
// data-draw-ms (mean time to draw a frame).
(function () {
  const body = document.body;
  const data = JSON.parse(document.getElementById("mason-data").textContent);
  const $ = (id) => document.getElementById(id);
  const playBtn = $("play"), speedSel = $("speed"), scrub = $("scrub"), clock = $("clock");
  let t = 0, playing = true, last = null, frames = 0;
  const end = data.end;
  scrub.max = String(end);
  scrub.step = String(end / 1000);
  const fmt = data.kind === "mission"
    ? (s) => Math.floor(s / 60) + ":" + (s % 60).toFixed(1).padStart(4, "0")
    : (s) => "step " + s.toFixed(1);
  playBtn.addEventListener("click", () => {
    if (!playing && t >= end) t = 0;
    playing = !playing;
    playBtn.textContent = playing ? "Pause" : "Play";
  });
  scrub.addEventListener("input", () => { t = parseFloat(scrub.value); draw(); });

  // Linear interpolation along a track of [t, x, y] points.
  function along(track, time) {
    let lo = 0, hi = track.length - 1;
    if (time <= track[0][0]) return [track[0][1], track[0][2], 0];
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (track[mid][0] <= time) lo = mid; else hi = mid - 1; }
    const a = track[lo], b = track[lo + 1];
    if (!b || b[0] <= a[0]) return [a[1], a[2], lo];
    const f = (time - a[0]) / (b[0] - a[0]);
    return [a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f, lo];
  }

  let draw;
  if (data.kind === "mission") {
    const top = $("top").getContext("2d"), front = $("front").getContext("2d");
    const A = data.arena, W = $("top").width, H = $("top").height;
    const s = Math.min(W / A.width, H / A.depth);
    const px = (x) => x * s, py = (y) => H - y * s;
    const pileColours = ["rgb(235,20,20)", "rgb(20,200,40)", "rgb(25,50,235)", "rgb(255,165,0)"];
    const uavColour = (i) => "hsl(" + ((i * 137.508) % 360).toFixed(0) + ",70%,45%)";
    // The wall from the front, its segments stacked (the layout comes with the data): as large
    // as fits the panel's width and 420 px of height, and the panel as tall as the wall.
    const F = $("front"), FW = data.front;
    const fs = Math.min((F.width - 20) / FW.width, 420 / FW.height, 150);
    F.height = Math.ceil(FW.height * fs + 20);
    draw = function () {
      top.fillStyle = "#f7f7f2"; top.fillRect(0, 0, W, H);
      const busy = data.zone.some((z) => z[0] <= t && t < z[1]);
      top.fillStyle = busy ? "rgba(67,160,71,0.35)" : "rgba(67,160,71,0.12)";
      top.fillRect(px(A.wall[0] - A.zone_half[0]), py(A.wall[1] + A.zone_half[1]), 2 * A.zone_half[0] * s, 2 * A.zone_half[1] * s);
      top.strokeStyle = "#555"; top.lineWidth = 4;
      top.beginPath(); top.moveTo(px(A.wall[0] - 2), py(A.wall[1])); top.lineTo(px(A.wall[0] + 2), py(A.wall[1])); top.stroke();
      A.piles.forEach((p, i) => { top.fillStyle = pileColours[i]; top.fillRect(px(p[0]) - 7, py(p[1]) - 7, 14, 14); });
      top.font = "bold 11px sans-serif"; top.textAlign = "center";
      const states = [];
      data.tracks.forEach((track, i) => {
        const [x, y, k] = along(track, t);
        top.fillStyle = uavColour(i);
        top.beginPath(); top.arc(px(x), py(y), 9, 0, 2 * Math.PI); top.fill();
        top.fillStyle = "#fff"; top.fillText(String(i), px(x), py(y) + 4);
        states.push("UAV " + i + ": " + track[k][3]);
      });
      top.textAlign = "start";
      $("states").textContent = states.join("  ·  ");
      front.fillStyle = "#fff"; front.fillRect(0, 0, F.width, F.height);
      front.fillStyle = "#555"; front.font = "12px sans-serif";
      FW.bands.forEach((band) => front.fillText("segment " + band.segment, 10, 10 + band.top * fs + 0.18 * fs));
      let placed = 0;
      data.bricks.forEach((b, i) => {
        const at = data.placed_at[i];
        const x = 10 + b.x0 * fs, w = (b.x1 - b.x0) * fs, y = 10 + b.y * fs, h = 0.2 * fs;
        if (at !== null && at <= t) { front.fillStyle = b.colour; front.fillRect(x, y, w, h); placed++; }
        front.strokeStyle = "#999"; front.lineWidth = 1; front.strokeRect(x + 0.5, y + 0.5, w - 1, h - 1);
      });
      $("status").textContent = placed + " / " + data.bricks.length + " bricks placed";
    };
  } else {
    const C = $("grid"), g = C.getContext("2d");
    const cell = Math.max(1, Math.min(24, Math.floor(900 / Math.max(data.width, data.height))));
    C.width = data.width * cell; C.height = data.height * cell;
    const map = document.createElement("canvas");
    map.width = C.width; map.height = C.height;
    const m = map.getContext("2d");
    m.fillStyle = "#f4f4f0"; m.fillRect(0, 0, map.width, map.height);
    m.fillStyle = "#3a3a3a";
    data.blocked.forEach((r) => m.fillRect(r[0] * cell, r[1] * cell, r[2] * cell, cell));
    const colour = data.paths.map((_, i) => "hsl(" + ((i * 137.508) % 360).toFixed(0) + ",70%,45%)");
    const xy = (c) => [c % data.width, Math.floor(c / data.width)];
    draw = function () {
      g.drawImage(map, 0, 0);
      const k = Math.floor(t), f = t - k;
      let arrived = 0;
      data.paths.forEach((p, i) => {
        const [gx, gy] = xy(data.goals[i]);
        g.strokeStyle = colour[i]; g.lineWidth = Math.max(1, cell / 5);
        g.strokeRect(gx * cell + 1, gy * cell + 1, cell - 2, cell - 2);
        const a = xy(p[Math.min(k, p.length - 1)]), b = xy(p[Math.min(k + 1, p.length - 1)]);
        const x = a[0] + (b[0] - a[0]) * f, y = a[1] + (b[1] - a[1]) * f;
        if (k >= p.length - 1) arrived++;
        g.fillStyle = colour[i];
        g.fillRect(x * cell + cell * 0.15, y * cell + cell * 0.15, cell * 0.7, cell * 0.7);
      });
      $("status").textContent = arrived + " / " + data.paths.length + " robots at their goals";
    };
  }

  let lastDrawn = 0, drawMs = 0;
  function frame(_, fromTimer) {
    // One clock for animation frames and timer frames alike.
    const now = performance.now();
    lastDrawn = now;
    if (last !== null && playing) {
      t = Math.min(end, t + (Math.max(0, now - last) / 1000) * parseFloat(speedSel.value));
      if (t >= end) { playing = false; playBtn.textContent = "Play"; }
    }
    last = now;
    scrub.value = String(t);
    clock.textContent = fmt(t) + " / " + fmt(end);
    const t0 = performance.now();
    draw();
    drawMs += performance.now() - t0;
    frames++;
    body.dataset.drawMs = (drawMs / frames).toFixed(2);
    body.dataset.t = t.toFixed(3);
    body.dataset.frames = String(frames);
    if (!fromTimer) requestAnimationFrame(frame);
  }
  requestAnimationFrame(frame);
  // Where animation frames are throttled (background tabs, headless browsers), a timer keeps
  // the replay going at 10 frames per second.
  setInterval(() => { if (performance.now() - lastDrawn > 90) frame(0, true); }, 100);
})();
