#include "scenarios/MatchReplay.h"

#include <cmath>

namespace nao::sim {

namespace {

double mm(double v) { return std::round(v * 1000) / 1000; }

const char* kStates[] = {"INITIAL", "READY", "SET", "PLAYING", "FINISHED"};

int stateIndex(const std::string& s) {
  for (int i = 0; i < 5; ++i)
    if (s == kStates[i]) return i;
  return 0;
}

// The page: data in a JSON script element, the drawing in plain JavaScript (no library).
const char* kPageHead = R"HTML(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>nao-soccer match replay</title>
<script>
// First: count script errors, the page's own included (the headless-browser test reads them).
window.addEventListener('error', function () {
  document.body.dataset.errors = String(Number(document.body.dataset.errors || 0) + 1);
});
</script>
<style>
body { font: 14px sans-serif; margin: 8px; background: #f4f4f4; }
#bar { display: flex; gap: 12px; align-items: center; margin-bottom: 6px; }
#scrub { flex: 1; }
#score { font-weight: bold; min-width: 80px; }
#events { height: 220px; overflow-y: auto; background: #fff; border: 1px solid #ccc; margin: 6px 0 0 0; padding: 4px 4px 4px 32px; }
#events li { cursor: pointer; }
#events li.now { background: #ffe9a8; }
.home { color: #1f4fff; } .away { color: #e02020; }
#legend span { margin-right: 14px; }
</style></head>
<body data-errors="0">
<div id="bar"><button id="play">pause</button>
<select id="speed"><option>1</option><option>2</option><option selected>4</option><option>8</option><option>16</option></select>x
<input id="scrub" type="range" min="0" value="0" step="1"><span id="time"></span><span id="state"></span><span id="score"></span></div>
<canvas id="field"></canvas>
<div id="legend"><span class="home">&#9679; home (filled: truth, ring: belief, small ring: its ball)</span><span class="away">&#9679; away</span><span style="color:#ff8000">&#9679; ball (truth)</span></div>
<ol id="events"></ol>
<script id="data" type="application/json">)HTML";

const char* kPageTail = R"HTML(</script>
<script>
'use strict';
const D = JSON.parse(document.getElementById('data').textContent);
const F = D.field, frames = D.frames, events = D.events, ppm = D.pixels_per_metre;
const I = {};
D.layout.forEach(function (name, i) { I[name] = i; });
const canvas = document.getElementById('field');
canvas.width = Math.round((F.length + 2 * F.border) * ppm);
canvas.height = Math.round((F.width + 2 * F.border) * ppm);
const g = canvas.getContext('2d');
const colours = ['#1f4fff', '#e02020'];
function px(x, y) { return [canvas.width / 2 + x * ppm, canvas.height / 2 - y * ppm]; }
function line(x0, y0, x1, y1) { const a = px(x0, y0), b = px(x1, y1); g.beginPath(); g.moveTo(a[0], a[1]); g.lineTo(b[0], b[1]); g.stroke(); }
function rect(x0, y0, x1, y1) { line(x0, y0, x1, y0); line(x1, y0, x1, y1); line(x1, y1, x0, y1); line(x0, y1, x0, y0); }
function disc(x, y, r, fill) { const a = px(x, y); g.beginPath(); g.arc(a[0], a[1], r, 0, 2 * Math.PI); g.fillStyle = fill; g.fill(); }
function ring(x, y, r, stroke, dash) { const a = px(x, y); g.beginPath(); g.setLineDash(dash || []); g.arc(a[0], a[1], r, 0, 2 * Math.PI); g.strokeStyle = stroke; g.stroke(); g.setLineDash([]); }
function drawField() {
  g.fillStyle = '#2e8b3a';
  g.fillRect(0, 0, canvas.width, canvas.height);
  g.strokeStyle = '#ffffff';
  g.lineWidth = Math.max(1, F.line_width * ppm);
  const hl = F.length / 2, hw = F.width / 2;
  rect(-hl, -hw, hl, hw);
  line(0, -hw, 0, hw);
  ring(0, 0, F.center_circle_diameter / 2 * ppm, '#ffffff');
  for (const s of [-1, 1]) {
    rect(s * hl, -F.penalty_area_width / 2, s * (hl - F.penalty_area_length), F.penalty_area_width / 2);
    if (F.goal_box_length > 0) rect(s * hl, -F.goal_box_width / 2, s * (hl - F.goal_box_length), F.goal_box_width / 2);
    const m = s * (hl - F.penalty_cross_distance), c = F.penalty_cross_size / 2;
    line(m - c, 0, m + c, 0); line(m, -c, m, c);
    g.strokeStyle = '#dddddd';
    line(s * hl, -F.goal_width / 2, s * (hl + F.goal_depth), -F.goal_width / 2);
    line(s * (hl + F.goal_depth), -F.goal_width / 2, s * (hl + F.goal_depth), F.goal_width / 2);
    line(s * (hl + F.goal_depth), F.goal_width / 2, s * hl, F.goal_width / 2);
    g.strokeStyle = '#ffffff';
  }
  line(-0.05, 0, 0.05, 0);
}
function drawRobot(fr, r) {
  const p = 'r' + r + '_', c = colours[r];
  g.globalAlpha = fr[I[p + 'penalised']] ? 0.35 : 1;
  const x = fr[I[p + 'x']], y = fr[I[p + 'y']], th = fr[I[p + 'theta']];
  disc(x, y, 0.15 * ppm, c);
  g.strokeStyle = '#000000'; g.lineWidth = 2;
  line(x, y, x + 0.25 * Math.cos(th), y + 0.25 * Math.sin(th));
  if (fr[I[p + 'belief_valid']]) {
    const bx = fr[I[p + 'belief_x']], by = fr[I[p + 'belief_y']], bt = fr[I[p + 'belief_theta']];
    g.lineWidth = 2;
    ring(bx, by, 0.2 * ppm, c, [6, 4]);
    g.strokeStyle = c;
    line(bx, by, bx + 0.3 * Math.cos(bt), by + 0.3 * Math.sin(bt));
  }
  if (fr[I[p + 'ball_valid']]) { g.lineWidth = 2; ring(fr[I[p + 'ball_x']], fr[I[p + 'ball_y']], 0.1 * ppm, c); }
  g.globalAlpha = 1;
}
const list = document.getElementById('events');
function describe(e) {
  const parts = [e.t.toFixed(1) + ' s', e.kind.replace('gc_', 'GameController: ')];
  for (const k of ['team', 'rule', 'how', 'reason', 'what', 'text']) if (e[k] !== undefined) parts.push(typeof e[k] === 'string' ? e[k] : JSON.stringify(e[k]));
  if (e.evidence !== undefined) parts.push('(' + (typeof e.evidence === 'string' ? e.evidence : JSON.stringify(e.evidence)) + ')');
  return parts.join('  ');
}
const items = events.map(function (e) {
  const li = document.createElement('li');
  li.textContent = describe(e);
  if (e.team === 'home' || e.team === 'away') li.className = e.team;
  li.addEventListener('click', function () { seek(e.t); pause(); });
  list.appendChild(li);
  return li;
});
const scrub = document.getElementById('scrub');
scrub.max = String(Math.max(0, frames.length - 1));
let index = 0, time = frames.length ? frames[0][I.t] : 0, playing = true, last = null, current = -1;
function frameAt(t) {
  let lo = 0, hi = frames.length - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (frames[mid][I.t] <= t) lo = mid; else hi = mid - 1; }
  return lo;
}
function draw() {
  drawField();
  if (!frames.length) return;
  const fr = frames[index];
  for (let b = 0; b < D.balls; ++b) disc(fr[I['ball' + b + '_x']], fr[I['ball' + b + '_y']], 0.07 * ppm, '#ff8000');
  for (let r = 0; r < 2; ++r) drawRobot(fr, r);
  document.getElementById('time').textContent = fr[I.t].toFixed(1) + ' s';
  document.getElementById('state').textContent = D.states[fr[I.state]];
  document.getElementById('score').textContent = 'home ' + fr[I.home_score] + ' : ' + fr[I.away_score] + ' away';
  scrub.value = String(index);
  let now = -1;
  for (let i = 0; i < events.length && events[i].t <= fr[I.t]; ++i) now = i;
  if (now !== current) {
    if (current >= 0) items[current].classList.remove('now');
    if (now >= 0) { items[now].classList.add('now'); items[now].scrollIntoView({block: 'nearest'}); }
    current = now;
  }
  document.body.dataset.time = String(fr[I.t]);
  document.body.dataset.frame = String(index);
}
function seek(t) { time = t; index = frameAt(t); draw(); }
function pause() { playing = false; document.getElementById('play').textContent = 'play'; }
document.getElementById('play').addEventListener('click', function () {
  playing = !playing; last = null;
  this.textContent = playing ? 'pause' : 'play';
  if (playing && index >= frames.length - 1) seek(frames[0][I.t]);
});
scrub.addEventListener('input', function () { index = Number(scrub.value); time = frames[index][I.t]; pause(); draw(); });
function tick(now) {
  if (playing && frames.length) {
    if (last !== null) time += (now - last) / 1000 * Number(document.getElementById('speed').value);
    if (time >= frames[frames.length - 1][I.t]) { time = frames[frames.length - 1][I.t]; pause(); }
    index = frameAt(time);
    draw();
  }
  last = now;
  requestAnimationFrame(tick);
}
const at = /t=([0-9.]+)/.exec(location.hash);
if (at) { pause(); seek(Number(at[1])); } else { draw(); }
const box = canvas.getBoundingClientRect();
document.body.dataset.canvas = Math.round(box.left + window.scrollX) + ',' + Math.round(box.top + window.scrollY);
document.body.dataset.frames = String(frames.length);
document.body.dataset.events = String(events.length);
document.body.dataset.ready = '1';
requestAnimationFrame(tick);
</script>
</body></html>
)HTML";

}  // namespace

Eigen::Vector2d replayPixel(const FieldDimensions& f, const Eigen::Vector2d& p) {
  const double w = std::round((f.length + 2 * f.borderStripWidth) * kReplayPixelsPerMetre);
  const double h = std::round((f.width + 2 * f.borderStripWidth) * kReplayPixelsPerMetre);
  return {w / 2 + p.x() * kReplayPixelsPerMetre, h / 2 - p.y() * kReplayPixelsPerMetre};
}

nlohmann::json replayData(const FieldDimensions& f, const std::vector<ReplayFrame>& frames, const nlohmann::json& events) {
  const std::size_t balls = frames.empty() ? 0 : frames.front().balls.size();
  // "r0_x", "ball3_y": appended piecewise (GCC 12 warns falsely on "literal" + std::string at -O2).
  auto name = [](const char* prefix, std::size_t i, const char* suffix) {
    std::string n(prefix);
    n += std::to_string(i);
    n += suffix;
    return n;
  };
  nlohmann::json layout = {"t", "state", "home_score", "away_score"};
  for (std::size_t r = 0; r < 2; ++r)
    for (const char* k : {"_x", "_y", "_theta", "_penalised", "_belief_valid", "_belief_x", "_belief_y", "_belief_theta",
                          "_ball_valid", "_ball_x", "_ball_y"})
      layout.push_back(name("r", r, k));
  for (std::size_t b = 0; b < balls; ++b) {
    layout.push_back(name("ball", b, "_x"));
    layout.push_back(name("ball", b, "_y"));
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const ReplayFrame& fr : frames) {
    nlohmann::json a = {mm(fr.t), stateIndex(fr.state), fr.score[0], fr.score[1]};
    for (const ReplayFrame::Robot& r : fr.robots)
      for (double v : {mm(r.pose.x()), mm(r.pose.y()), mm(r.pose.z()), r.penalised ? 1.0 : 0.0, r.beliefValid ? 1.0 : 0.0,
                       mm(r.belief.x()), mm(r.belief.y()), mm(r.belief.z()), r.ballValid ? 1.0 : 0.0, mm(r.ball.x()), mm(r.ball.y())})
        a.push_back(v);
    for (std::size_t b = 0; b < balls; ++b) {
      a.push_back(mm(fr.balls[b].x()));
      a.push_back(mm(fr.balls[b].y()));
    }
    rows.push_back(std::move(a));
  }
  return {{"field",
           {{"length", f.length}, {"width", f.width}, {"border", f.borderStripWidth}, {"line_width", f.lineWidth},
            {"center_circle_diameter", f.centerCircleDiameter}, {"penalty_area_length", f.penaltyAreaLength},
            {"penalty_area_width", f.penaltyAreaWidth}, {"goal_box_length", f.hasGoalBox ? f.goalBoxAreaLength : 0.0},
            {"goal_box_width", f.goalBoxAreaWidth}, {"penalty_cross_distance", f.penaltyCrossDistance},
            {"penalty_cross_size", f.penaltyCrossSize}, {"goal_width", f.goalInnerWidth}, {"goal_depth", f.goalDepth}}},
          {"pixels_per_metre", kReplayPixelsPerMetre},
          {"states", kStates},
          {"balls", balls},
          {"layout", layout},
          {"frames", rows},
          {"events", events}};
}

std::string replayHtml(const nlohmann::json& data) {
  std::string json = data.dump();
  // "</" inside the data would end its script element early; "<\/" is the same JSON string.
  for (std::size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 3)) json.replace(at, 2, "<\\/");
  return std::string(kPageHead) + json + kPageTail;
}

}  // namespace nao::sim
