(function () {
'use strict';
var D = JSON.parse(document.getElementById('data').textContent);
var S = D.summary, VC = S.vc_nominal;
// Without a model (S.normals): the normals from the toolpath; no gouge
// check and no cusp map, so their parts are left out of the page.
var N = S.normals || null;
function fmt(v, d) { return (v === null || v === undefined || !isFinite(v)) ? '\u2013' : Number(v).toFixed(d); }
function pct(v) { return fmt(100 * v, 1) + ' %'; }
function el(tag, cls, text) { var e = document.createElement(tag); if (cls) e.className = cls; if (text !== undefined) e.textContent = text; return e; }
function pairs(flat) { var out = new Array(flat.length / 2); for (var i = 0; i < out.length; ++i) out[i] = {x: flat[2 * i], y: flat[2 * i + 1]}; return out; }

document.getElementById('title').textContent = 'vcpost report: ' + S.inputs.program;
document.getElementById('subtitle').textContent =
  (N ? 'no model: normals from the toolpath' : 'model ' + S.inputs.model.file + ' (' + S.inputs.model.kind + ', ' + S.inputs.model.description + ')') + '  \u00b7  tool ' +
  S.inputs.tool + '  \u00b7  vc ' + VC + ' m/min  \u00b7  ap ' + S.inputs.ap + ' mm  \u00b7  ae ' +
  (S.inputs.ae === null ? 'measured' : S.inputs.ae + ' mm') + '  \u00b7  policy ' + S.inputs.policy +
  '  \u00b7  machine ' + S.profile.name + ' (' + S.profile.n_min_rpm + '\u2013' + S.profile.n_max_rpm + ' rpm)';

// Summary cards.
var cards = document.getElementById('cards');
function card(key, value, note, cls) {
  var c = el('div', 'card' + (cls ? ' ' + cls : ''));
  c.appendChild(el('div', 'k', key));
  var v = el('div', 'v', value);
  if (note) { v.appendChild(document.createTextNode(' ')); v.appendChild(el('small', '', note)); }
  c.appendChild(v); cards.appendChild(c);
}
var B = S.before, A = S.after;
function grade(share) { return share >= 0.9 ? 'good' : share >= 0.6 ? 'warn' : 'bad'; }
card('Cutting time within \u00b110 % of vc', pct(A.within_10_percent), 'after (' + pct(B.within_10_percent) + ' before)', grade(A.within_10_percent));
card('Cutting time within \u00b15 %', pct(A.within_5_percent), 'after (' + pct(B.within_5_percent) + ' before)', grade(A.within_5_percent));
card('Mean vc', fmt(A.vc && A.vc.mean, 1), 'm/min after (' + fmt(B.vc && B.vc.mean, 1) + ' before)');
card('vc p5 \u2013 p95 after', fmt(A.vc && A.vc.p5, 1) + '\u2013' + fmt(A.vc && A.vc.p95, 1), 'm/min (before ' + fmt(B.vc && B.vc.p5, 0) + '\u2013' + fmt(B.vc && B.vc.p95, 0) + ')');
card('Clamped at n_max', fmt(A.time_s.clamped_n_max, 1) + ' s', 'after; ' + pct(A.time_s.clamped_n_max / Math.max(S.time_s.cutting, 1e-12)) + ' of cutting', A.time_s.clamped_n_max > 0 ? 'warn' : 'good');
card('Slew limit binds', fmt(A.time_s.slew, 1) + ' s', 'spindle acceleration', A.time_s.slew > 0.05 * S.time_s.cutting ? 'warn' : '');
if (N) {
  card('No model', 'no gouge check, no cusp map', 'the surface is known only where the path lies', 'warn');
  card('Normals from the toolpath', N.two_sided + ' / ' + N.one_sided + ' / ' + N.kept,
       'two-sided / one-sided / none (the program\u2019s S) of ' + S.points.total + ' points', N.kept > 0 ? 'warn' : 'good');
} else {
  card('No contact / gouge', S.points.no_contact + ' / ' + S.points.gouging, 'of ' + S.points.total + ' points', S.points.gouging > 0 ? 'bad' : (S.points.no_contact > 0 ? 'warn' : 'good'));
}
card('S words written', String(S.words_written.s), S.inputs.adjust_feed ? (S.words_written.f + ' F words') : 'F unchanged');
S.sections.forEach(function (q) {
  var a = q.stock_mm;
  if (!q.posted || !a || (a.radial === 0 && a.axial === 0)) return;
  var two = a.radial !== a.axial;
  card('Allowance' + (q.tool_number !== null ? ' T' + q.tool_number : ''), fmt(a.radial, 3) + (two ? ' / ' + fmt(a.axial, 3) : '') + ' mm',
       (two ? 'radial / axial; ' : '') + 'contact with the model offset by it (--stock)');
});
var P = S.s_placement, placed = P.mode === 'at_stops' ? 'at stops' : P.mode === 'priced' ? 'at stops, and in feed where worth the stop' : 'inline';
card('S words placed ' + placed, String(P.s_words), P.in_feed + ' inside feed streams; ' + P.stops + ' path stops \u00d7 ' +
     fmt(P.stop_cost_s, 3) + ' s = ' + fmt(P.time_cost_s, 2) + ' s on this control', P.mode === 'at_stops' && P.in_feed > 0 ? 'warn' : '');
P.sections.slice(0, 8).forEach(function (q, i) {
  card('Section ' + (i + 1) + ' from ' + fmt(q.start_s, 1) + ' s: S ' + placed, q.s_words + ' words',
       q.in_feed + ' in feed, ' + fmt(q.time_cost_s, 2) + ' s; within \u00b110 % of vc ' + pct(q.within_10_percent_before) +
       ' \u2192 ' + pct(q.within_10_percent_after));
});
if (!N) {
  card('Cusp height', fmt(S.surface.cusp_um && S.surface.cusp_um.mean, 2), 'um mean, max ' + fmt(S.surface.cusp_um && S.surface.cusp_um.max, 2));
  card('Ra / Rz (across the feed)', fmt(S.surface.ra_um && S.surface.ra_um.mean, 2) + ' / ' + fmt(S.surface.rz_um && S.surface.rz_um.mean, 2), 'um, means');
}
card('Cutting time', fmt(S.time_s.cutting, 1) + ' s', 'program ' + fmt(S.time_s.program, 1) + ' s');
card('Points evaluated', String(S.points.total), S.points.cutting + ' cutting, run ' + fmt(S.run_time_s, 2) + ' s');

// Charts (Chart.js).
Chart.defaults.animation = false;
Chart.defaults.font.size = 11;
var vcBefore = pairs(D.vc.before), vcAfter = pairs(D.vc.after);
var tEnd = Math.max(vcAfter.length ? vcAfter[vcAfter.length - 1].x : 1, D.s.after.length ? D.s.after[D.s.after.length - 2] : 1);
function band(lo, hi, label) {
  return [{label: label, data: [{x: 0, y: lo}, {x: tEnd, y: lo}], borderWidth: 0, pointRadius: 0, fill: false, backgroundColor: 'rgba(0,0,0,0)'},
          {label: label + ' ', data: [{x: 0, y: hi}, {x: tEnd, y: hi}], borderWidth: 0, pointRadius: 0, fill: '-1', backgroundColor: 'rgba(40,160,90,0.12)'}];
}
function lineSet(label, data, color, width, dash) {
  return {label: label, data: data, borderColor: color, backgroundColor: color, borderWidth: width, pointRadius: 0,
          borderDash: dash || [], fill: false, spanGaps: true, tension: 0};
}
var timeScale = {type: 'linear', title: {display: true, text: 'cutting time, s'}, min: 0, max: tEnd};
// Tool sections: a vertical line where each one's evaluated points start.
var marks = (S.section_marks || []).length > 1 ? S.section_marks : [];
function markSets(lo, hi) {
  return marks.map(function (m) { return lineSet(m.label, [{x: m.cutting_time_s, y: lo}, {x: m.cutting_time_s, y: hi}], '#6b7280', 1, [2, 2]); });
}
function legendFilter(item) { return !/\u00b1/.test(item.text); }
var vcChart = new Chart(document.getElementById('vcplot'), {
  type: 'line',
  data: {datasets: band(0.9 * VC, 1.1 * VC, '\u00b110 %').concat(band(0.95 * VC, 1.05 * VC, '\u00b15 %'), [
    lineSet('nominal ' + VC + ' m/min', [{x: 0, y: VC}, {x: tEnd, y: VC}], '#2e8b57', 1, [4, 3]),
    lineSet('before (program S)', vcBefore, '#d9822b', 1),
    lineSet('after (vcpost)', vcAfter, '#1f6fd1', 1.3)], markSets(0, 1.5 * VC))},
  options: {responsive: true, maintainAspectRatio: false, parsing: false, normalized: true,
            interaction: {mode: 'nearest', axis: 'x', intersect: false},
            plugins: {legend: {labels: {filter: legendFilter}}, decimation: {enabled: false}},
            scales: {x: timeScale, y: {title: {display: true, text: 'vc, m/min'}}}}
});
var sBefore = pairs(D.s.before), sAfter = pairs(D.s.after);
var sChart = new Chart(document.getElementById('splot'), {
  type: 'line',
  data: {datasets: [
    lineSet('n_max ' + S.profile.n_max_rpm, [{x: 0, y: S.profile.n_max_rpm}, {x: tEnd, y: S.profile.n_max_rpm}], '#b91c1c', 1, [6, 3]),
    lineSet('n_min ' + S.profile.n_min_rpm, [{x: 0, y: S.profile.n_min_rpm}, {x: tEnd, y: S.profile.n_min_rpm}], '#7c3aed', 1, [6, 3]),
    lineSet('S before', sBefore, '#d9822b', 1),
    lineSet('S after', sAfter, '#1f6fd1', 1.3)].concat(markSets(0, S.profile.n_max_rpm))},
  options: {responsive: true, maintainAspectRatio: false, parsing: false, normalized: true,
            interaction: {mode: 'nearest', axis: 'x', intersect: false},
            scales: {x: JSON.parse(JSON.stringify(timeScale)), y: {title: {display: true, text: 'S, rpm'}, min: 0}}}
});

// Drag to zoom on either time plot; both follow.
var timeCharts = [vcChart, sChart];
function setRange(lo, hi) {
  timeCharts.forEach(function (c) { c.options.scales.x.min = lo; c.options.scales.x.max = hi; c.update('none'); });
}
function zoomable(chart, boxId) {
  var canvas = chart.canvas, box = document.getElementById(boxId), start = null;
  function px(e) { var r = canvas.getBoundingClientRect(); return e.clientX - r.left; }
  canvas.addEventListener('mousedown', function (e) { start = px(e); });
  canvas.addEventListener('mousemove', function (e) {
    if (start === null) return;
    var a = Math.min(start, px(e)), b = Math.max(start, px(e));
    box.style.display = 'block'; box.style.left = a + 'px'; box.style.width = (b - a) + 'px';
  });
  window.addEventListener('mouseup', function (e) {
    if (start === null) return;
    var a = Math.min(start, px(e)), b = Math.max(start, px(e));
    start = null; box.style.display = 'none';
    if (b - a < 4) return;
    var x = chart.scales.x;
    setRange(x.getValueForPixel(a), x.getValueForPixel(b));
  });
  canvas.addEventListener('dblclick', function () { setRange(0, tEnd); });
}
zoomable(vcChart, 'vczoom');
zoomable(sChart, 'szoom');
document.getElementById('zoomreset').addEventListener('click', function () { setRange(0, tEnd); });

// Histogram of the deviation.
var labels = [], hb = [], ha = [], step = D.hist.step_pct, lim = D.hist.limit_pct;
var tb = D.hist.before_s.reduce(function (a, b) { return a + b; }, 0) || 1;
var ta = D.hist.after_s.reduce(function (a, b) { return a + b; }, 0) || 1;
for (var i = 0; i < D.hist.after_s.length; ++i) {
  var lo = -lim + i * step;
  labels.push((i === 0 ? '\u2264' : '') + lo.toFixed(0) + (i === D.hist.after_s.length - 1 ? '+' : ''));
  hb.push(100 * D.hist.before_s[i] / tb); ha.push(100 * D.hist.after_s[i] / ta);
}
new Chart(document.getElementById('histplot'), {
  type: 'bar',
  data: {labels: labels, datasets: [
    {label: 'before', data: hb, backgroundColor: 'rgba(217,130,43,0.75)', barPercentage: 1, categoryPercentage: 1},
    {label: 'after', data: ha, backgroundColor: 'rgba(31,111,209,0.75)', barPercentage: 1, categoryPercentage: 1}]},
  options: {responsive: true, maintainAspectRatio: false,
            scales: {x: {title: {display: true, text: 'vc / vc_nominal - 1, %'}, ticks: {maxRotation: 0, autoSkip: true, maxTicksLimit: 11}},
                     y: {title: {display: true, text: '% of cutting time'}, beginAtZero: true}}}
});

// Top views: our own raster drawing of the plan grids. Each occupied cell
// also paints its empty neighbours (worst value wins), so passes a few
// cells apart read as a surface.
var G = D.grid;
function unpack(values) {
  var full = new Float32Array(G.nx * G.ny).fill(NaN), at = 0;
  for (var k = 0; k < G.index_gaps.length; ++k) { at += G.index_gaps[k]; if (values[k] !== null) full[at] = values[k]; }
  var out = new Float32Array(full);
  for (var j = 0; j < G.ny; ++j) for (var i = 0; i < G.nx; ++i) {
    var o = j * G.nx + i; if (!isNaN(full[o])) continue;
    var best = NaN;
    for (var dj = -1; dj <= 1; ++dj) for (var di = -1; di <= 1; ++di) {
      var ii = i + di, jj = j + dj; if (ii < 0 || jj < 0 || ii >= G.nx || jj >= G.ny) continue;
      var v = full[jj * G.nx + ii]; if (!isNaN(v) && (isNaN(best) || Math.abs(v) > Math.abs(best))) best = v;
    }
    out[o] = best;
  }
  return out;
}
var gridBefore = unpack(G.before_pct), gridAfter = unpack(G.after_pct), gridCusp = unpack(G.cusp_um);
function mix(a, b, f) { return [Math.round(a[0] + f * (b[0] - a[0])), Math.round(a[1] + f * (b[1] - a[1])), Math.round(a[2] + f * (b[2] - a[2]))]; }
function devColor(p) {
  // Green within +-5 % of nominal (darker nearer it); blue slower, red faster; saturates at 20 %.
  var t = Math.max(-1, Math.min(1, p / 20));
  if (Math.abs(t) <= 0.25) return mix([46, 150, 90], [178, 222, 170], Math.abs(t) / 0.25);
  return t < 0 ? mix([150, 185, 235], [25, 55, 170], (-t - 0.25) / 0.75)
               : mix([245, 195, 120], [190, 25, 35], (t - 0.25) / 0.75);
}
var ramp = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
function seqColor(t) {
  t = Math.max(0, Math.min(1, t)) * (ramp.length - 1);
  var k = Math.min(ramp.length - 2, Math.floor(t));
  return mix(ramp[k], ramp[k + 1], t - k);
}
function drawMap(canvasId, values, color, tipId, unit) {
  var canvas = document.getElementById(canvasId);
  canvas.width = G.nx; canvas.height = G.ny;
  var ctx = canvas.getContext('2d'), img = ctx.createImageData(G.nx, G.ny);
  for (var j = 0; j < G.ny; ++j) {
    for (var i = 0; i < G.nx; ++i) {
      var v = values[j * G.nx + i], o = 4 * ((G.ny - 1 - j) * G.nx + i);  // y up
      var c = isNaN(v) ? [238, 241, 245] : color(v);
      img.data[o] = c[0]; img.data[o + 1] = c[1]; img.data[o + 2] = c[2]; img.data[o + 3] = 255;
    }
  }
  ctx.putImageData(img, 0, 0);
  var tip = document.getElementById(tipId);
  canvas.onmousemove = function (e) {
    var r = canvas.getBoundingClientRect();
    var i = Math.floor((e.clientX - r.left) / r.width * G.nx), j = G.ny - 1 - Math.floor((e.clientY - r.top) / r.height * G.ny);
    var v = (i >= 0 && j >= 0 && i < G.nx && j < G.ny) ? values[j * G.nx + i] : NaN;
    if (isNaN(v)) { tip.style.display = 'none'; return; }
    tip.textContent = 'x ' + (G.x0 + (i + 0.5) * G.cell).toFixed(1) + ', y ' + (G.y0 + (j + 0.5) * G.cell).toFixed(1) + ' mm: ' + v.toFixed(2) + ' ' + unit;
    tip.style.display = 'block'; tip.style.left = (e.clientX - r.left + 12) + 'px'; tip.style.top = (e.clientY - r.top + 12) + 'px';
  };
  canvas.onmouseleave = function () { tip.style.display = 'none'; };
}
function legend(canvasId, color) {
  var c = document.getElementById(canvasId), ctx = c.getContext('2d');
  for (var x = 0; x < c.width; ++x) { var k = color(x / (c.width - 1)); ctx.fillStyle = 'rgb(' + k.join(',') + ')'; ctx.fillRect(x, 0, 1, c.height); }
}
function showDev(which) {
  drawMap('devmap', which === 'before' ? gridBefore : gridAfter, devColor, 'devtip', '%');
  document.getElementById('showbefore').className = which === 'before' ? 'on' : '';
  document.getElementById('showafter').className = which === 'after' ? 'on' : '';
}
document.getElementById('showbefore').addEventListener('click', function () { showDev('before'); });
document.getElementById('showafter').addEventListener('click', function () { showDev('after'); });
showDev('after');
legend('devlegend', function (t) { return devColor(40 * t - 20); });
// The cusp scale tops out a little above the 95th percentile, so a few
// first-contact outliers do not wash the map out.
if (N) {
  document.getElementById('cuspsection').remove();
} else {
  var cuspTop = S.surface.cusp_um ? Math.min(S.surface.cusp_um.max, 1.25 * S.surface.cusp_um.p95) : 1;
  cuspTop = cuspTop > 0 ? cuspTop : 1;
  drawMap('cuspmap', gridCusp, function (v) { return seqColor(v / cuspTop); }, 'cusptip', 'um');
  legend('cusplegend', seqColor);
  document.getElementById('cuspmax').textContent = (S.surface.cusp_um && cuspTop < S.surface.cusp_um.max ? '\u2265 ' : '') + cuspTop.toFixed(1) + ' um';
}
// The real ap (in-process stock only): the scale tops out at twice the
// nominal --ap or the highest ap, whichever is lower.
var extraMaps = [];
if (G.ap_mm && S.stock) {
  document.getElementById('apsection').hidden = false;
  var apTop = Math.max(1e-3, Math.min(S.stock.ap_max_mm, 2 * S.stock.ap_nominal_mm));
  drawMap('apmap', unpack(G.ap_mm), function (v) { return seqColor(v / apTop); }, 'aptip', 'mm');
  legend('aplegend', seqColor);
  document.getElementById('apmax').textContent = (apTop < S.stock.ap_max_mm ? '\u2265 ' : '') + apTop.toFixed(2) + ' mm';
  document.getElementById('apnominal').textContent = '(--ap ' + S.stock.ap_nominal_mm + ' mm)';
  extraMaps.push('apmap');
}

// Worst regions.
function regionTable(id, rows, side) {
  var host = document.getElementById(id);
  if (!rows.length) { host.appendChild(el('p', '', 'None: vc stays within the threshold over the whole cut.')); return; }
  var t = el('table'), head = el('tr');
  ['#', 'NC lines', 'from, s', 'duration, s', 'worst, %', 'vc min\u2013max, m/min', 'worst at x, y (mm)', side === 'after' ? 'what decided S' : ''].forEach(function (h, k) {
    head.appendChild(el('th', k === 1 || k === 7 ? 'l' : '', h));
  });
  t.appendChild(head);
  rows.forEach(function (r, k) {
    var tr = el('tr');
    tr.appendChild(el('td', '', String(k + 1)));
    tr.appendChild(el('td', 'l', r.first_line === r.last_line ? String(r.first_line) : r.first_line + '\u2013' + r.last_line));
    tr.appendChild(el('td', '', fmt(r.start_s, 2)));
    tr.appendChild(el('td', '', fmt(r.duration_s, 3)));
    tr.appendChild(el('td', r.worst_pct < 0 ? 'neg' : 'pos', (r.worst_pct > 0 ? '+' : '') + fmt(r.worst_pct, 1)));
    tr.appendChild(el('td', '', fmt(r.vc_min, 1) + '\u2013' + fmt(r.vc_max, 1)));
    tr.appendChild(el('td', '', fmt(r.x, 1) + ', ' + fmt(r.y, 1)));
    tr.appendChild(el('td', 'l', side === 'after' ? r.bound : ''));
    t.appendChild(tr);
  });
  host.appendChild(t);
}
document.getElementById('afterhint').textContent = 'stretches with |vc/vc_nom - 1| > ' + D.regions.after_threshold_pct + ' %, ranked by time \u00d7 deviation';
document.getElementById('beforehint').textContent = 'with the program\u2019s own S: stretches off nominal by more than ' + D.regions.before_threshold_pct + ' %';
regionTable('regionsafter', D.regions.after, 'after');
regionTable('regionsbefore', D.regions.before, 'before');

document.getElementById('footer').textContent = 'vcpost report \u00b7 ' + S.points.total + ' points; plots show the minimum and maximum of every ' +
  D.bucket_points + ' consecutive point(s); the per-point CSV (vcpost report -o FILE.csv) has every point. ' +
  (N ? 'No model: each point\u2019s normal from the toolpath (its CSV column normal says how), no gouge check, no cusp map.'
     : 'Cusp and Ra/Rz: MODELS.md section 3 (transverse profile, passes ae apart).');

// Self-check for tests: which canvases carry ink, and any script errors.
function inked(canvas) {
  var ctx = canvas.getContext('2d');
  if (!ctx || !canvas.width || !canvas.height) return false;
  var d = ctx.getImageData(0, 0, canvas.width, canvas.height).data, n = 0;
  for (var k = 3; k < d.length; k += 4) if (d[k] !== 0) { if (++n > 50) return true; }
  return false;
}
var ids = ['vcplot', 'histplot', 'splot', 'devmap'].concat(N ? [] : ['cuspmap'], extraMaps), drawn = ids.filter(function (id) { return inked(document.getElementById(id)); });
// The section marks the vc plot draws: label and time.
var drawnMarks = vcChart.data.datasets.filter(function (ds) { return marks.some(function (m) { return m.label === ds.label; }); })
  .map(function (ds) { return {label: ds.label, x: ds.data[0].x}; });
document.getElementById('selfcheck').textContent = JSON.stringify({canvases: ids, drawn: drawn, errors: window.__vcpostErrors,
  chart: typeof Chart === 'function' ? Chart.version : null, marks: drawnMarks});
document.body.setAttribute('data-drawn', String(drawn.length));
})();
