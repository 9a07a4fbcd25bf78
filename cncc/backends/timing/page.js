/* The timing page's script (cncc/backends/timing/page.js, inlined by html.py).
   Reads the JSON in #cncc-data (pagedata.py), draws the speed chart and the tool-path
   views on canvases, links plots, tables and the selected line.  No network, no library.
   API for tests and scripts: window.cnccTiming (see the end). */
(function () {
  'use strict';
  var D = JSON.parse(document.getElementById('cncc-data').textContent);
  var COL = D.colors;
  function dec(s, T) {
    var b = atob(s), u = new Uint8Array(b.length);
    for (var i = 0; i < b.length; i++) u[i] = b.charCodeAt(i);
    return new T(u.buffer);
  }
  function el(id) { return document.getElementById(id); }
  function hms(s) {
    s = Math.max(0, Math.round(s));
    var h = Math.floor(s / 3600), m = Math.floor(s / 60) % 60, r = s % 60;
    return h + ':' + (m < 10 ? '0' : '') + m + ':' + (r < 10 ? '0' : '') + r;
  }
  function fmt(v) {
    var a = Math.abs(v);
    if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(2);
    return String(Math.round(v * 1000) / 1000);
  }
  function ticks(lo, hi, count) {
    if (!(hi > lo)) return [lo];
    var raw = (hi - lo) / Math.max(count - 1, 1), mag = Math.pow(10, Math.floor(Math.log10(raw)));
    var steps = [1, 2, 2.5, 5, 10], step = mag * 10;
    for (var k = 0; k < steps.length; k++) if (steps[k] * mag >= raw) { step = steps[k] * mag; break; }
    var out = [], first = Math.ceil(lo / step - 1e-9) * step;
    for (var t = first; t <= hi + step * 1e-9; t += step) out.push(Math.abs(t) < step * 1e-9 ? 0 : t);
    return out;
  }
  function setup(canvas) {
    var dpr = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
    canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    var ctx = canvas.getContext('2d');
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, w, h);
    ctx.font = '11px sans-serif';
    return {ctx: ctx, w: w, h: h};
  }

  // ---- lines and the selection -------------------------------------------------------
  var LINES = {};
  (function () {
    var L = D.lines;
    for (var k = 0; k < L.i.length; k++) LINES[L.i[k]] = {i: L.i[k], line: L.line[k], n: L.n[k], text: L.texts[L.t[k]], file: L.files[L.f[k]]};
  })();
  var selected = null, tip = el('tip');
  function describe(i) {
    var r = LINES[i];
    if (!r) return 'line ?';
    return 'line ' + r.line + (r.n ? ' · ' + r.n : '') + ' · ' + r.text;
  }
  function showTip(x, y, text) {
    if (text === null) { tip.style.display = 'none'; return; }
    tip.textContent = text; tip.style.display = 'block';
    tip.style.left = (x + 14) + 'px'; tip.style.top = (y + 14) + 'px';
  }
  function select(i) {
    selected = (i === null || i === undefined || i < 0) ? null : i;
    var bar = el('selected');
    bar.textContent = selected === null ? 'Click a point of a plot or a table row to select its line.' : 'Selected: ' + describe(selected);
    document.querySelectorAll('tr.sel').forEach(function (tr) { tr.classList.remove('sel'); });
    if (selected !== null) document.querySelectorAll('tr[data-i="' + selected + '"]').forEach(function (tr) { tr.classList.add('sel'); });
    drawPaths(); drawSpeed();
  }

  // ---- speed over time ---------------------------------------------------------------
  function series(s) {
    if (!s) return null;
    return {vmin: dec(s.vmin, Float32Array), vmax: dec(s.vmax, Float32Array), limit: dec(s.limit, Int8Array),
            top: dec(s.top, Int8Array), vlimit: dec(s.vlimit, Float32Array),
            line: dec(s.line, Int32Array), max: s.max, label: s.label};
  }
  var SP = series(D.speed), NOM = series(D.nominal), NC = D.columns, END = D.end_s;
  var view = {t0: 0, t1: END};
  var SM = {left: 64, right: 12, top: 10, bottom: 34};
  var vtop = Math.max(SP.max, NOM ? NOM.max : 0, 1) * 1.06;
  var units = [];  // what the chart shows: one entry per pixel (or per column when zoomed in)
  function colOf(t) { return Math.min(NC - 1, Math.max(0, Math.floor(t / END * NC))); }
  // Columns c0..c1 merged: min of mins, max of maxes, the limit most columns have (and the highest
  // speed seen under it), the limit at the highest speed.  Every value and colour comes from a column.
  function reduce(S, c0, c1) {
    var lo = Infinity, hi = -Infinity, line = -1, top = -1, count = new Array(D.limits.length).fill(0);
    for (var c = c0; c < c1; c++) {
      if (S.vmax[c] < 0) continue;
      if (S.vmin[c] < lo) lo = S.vmin[c];
      if (S.vmax[c] > hi) { hi = S.vmax[c]; line = S.line[c]; top = S.top ? S.top[c] : -1; }
      if (S.limit[c] >= 0) count[S.limit[c]]++;
    }
    var lim = -1, best = 0, vlim = -1;
    for (var k = 0; k < count.length; k++) if (count[k] > best) { best = count[k]; lim = k; }
    if (S.vlimit) for (c = c0; c < c1; c++) if (S.limit[c] === lim && S.vlimit[c] > vlim) vlim = S.vlimit[c];
    return {lo: lo, hi: hi, limit: lim, line: line, top: top, vlim: vlim};
  }
  function drawSpeed() {
    var cv = el('speed'), g = setup(cv), ctx = g.ctx;
    var pw = g.w - SM.left - SM.right, ph = g.h - SM.top - SM.bottom;
    function X(t) { return SM.left + (t - view.t0) / (view.t1 - view.t0) * pw; }
    function Y(v) { return SM.top + (1 - v / vtop) * ph; }
    ctx.strokeStyle = '#999'; ctx.strokeRect(SM.left, SM.top, pw, ph);
    ctx.fillStyle = '#333'; ctx.textAlign = 'right';
    ticks(0, vtop, 6).forEach(function (v) {
      var y = Y(v); if (y < SM.top - 0.5) return;
      ctx.strokeStyle = '#eee'; ctx.beginPath(); ctx.moveTo(SM.left, y); ctx.lineTo(SM.left + pw, y); ctx.stroke();
      ctx.fillText(fmt(v), SM.left - 4, y + 4);
    });
    var span = view.t1 - view.t0, useHms = span > 600;
    ctx.textAlign = 'center';
    ticks(view.t0, view.t1, Math.max(3, Math.floor(pw / 110))).forEach(function (t) {
      var x = X(t);
      ctx.strokeStyle = '#eee'; ctx.beginPath(); ctx.moveTo(x, SM.top); ctx.lineTo(x, SM.top + ph); ctx.stroke();
      ctx.fillText(useHms ? hms(t) : fmt(t), x, SM.top + ph + 14);
    });
    ctx.fillText(useHms ? 'time [h:mm:ss]' : 'time [s]', SM.left + pw / 2, g.h - 4);
    ctx.save(); ctx.translate(12, SM.top + ph / 2); ctx.rotate(-Math.PI / 2); ctx.fillText('path speed [mm/min]', 0, 0); ctx.restore();
    ctx.save(); ctx.beginPath(); ctx.rect(SM.left, SM.top, pw, ph); ctx.clip();
    ctx.globalAlpha = 0.22;
    D.bands.forEach(function (b) {
      if (b[1] < view.t0 || b[0] > view.t1) return;
      ctx.fillStyle = COL.category[b[2]];
      ctx.fillRect(X(b[0]), SM.top, Math.max(X(b[1]) - X(b[0]), 1), ph);
    });
    ctx.globalAlpha = 1;
    var c0 = colOf(view.t0), c1 = Math.min(NC, colOf(view.t1) + 1), perPx = (c1 - c0) / pw;
    units = [];
    if (perPx <= 1) {
      for (var c = c0; c < c1; c++) units.push({c0: c, c1: c + 1, x0: X(c / NC * END), x1: X((c + 1) / NC * END)});
    } else {
      var prev = c0;
      for (var p = 1; p <= Math.ceil(pw); p++) {
        var cend = Math.min(c1, Math.max(prev + 1, Math.floor(c0 + p * perPx)));
        if (cend > prev) units.push({c0: prev, c1: cend, x0: X(prev / NC * END), x1: X(cend / NC * END)});
        prev = cend;
        if (prev >= c1) break;
      }
    }
    if (NOM) {
      ctx.strokeStyle = '#222'; ctx.lineWidth = 1.2; ctx.setLineDash([5, 4]); ctx.beginPath();
      var pen = false;
      units.forEach(function (u) {
        var r = reduce(NOM, u.c0, u.c1); u.n = r;
        if (r.hi < 0) { pen = false; return; }
        if (!pen) ctx.moveTo(u.x0, Y(r.hi)); else ctx.lineTo(u.x0, Y(r.hi));
        ctx.lineTo(u.x1, Y(r.hi)); pen = true;
      });
      ctx.stroke(); ctx.setLineDash([]); ctx.lineWidth = 1;
    }
    units.forEach(function (u) {
      var r = reduce(SP, u.c0, u.c1); u.r = r;
      if (r.hi < 0) return;
      var ya = Y(r.hi), yb = Y(r.lo), w = Math.max(u.x1 - u.x0, 1);
      if (yb - ya < 2) { ya -= 1; yb = ya + 2; }
      ctx.fillStyle = r.limit >= 0 ? COL.limit[D.limits[r.limit]] : '#000';
      ctx.fillRect(u.x0, ya, w, yb - ya);
      if (r.top >= 0 && r.top !== r.limit && r.vlim >= 0 && r.hi > r.vlim) {  // above the speeds under the
        var ym = Y(r.vlim);                                                     // main limit: the top's limit
        ctx.fillStyle = COL.limit[D.limits[r.top]];
        ctx.fillRect(u.x0, ya, w, Math.max(ym - ya, 1));
      }
    });
    if (selected !== null) {
      ctx.strokeStyle = '#000'; ctx.lineWidth = 2;
      units.forEach(function (u) { if (u.r && u.r.line === selected) { ctx.strokeRect(u.x0 - 1, SM.top + 1, Math.max(u.x1 - u.x0, 1) + 2, ph - 2); } });
      ctx.lineWidth = 1;
    }
    ctx.restore();
    el('speed-range').textContent = (useHms ? hms(view.t0) + ' – ' + hms(view.t1) : fmt(view.t0) + ' – ' + fmt(view.t1) + ' s') +
      ' of ' + hms(END) + ' (' + fmt(END) + ' s)';
  }
  function unitAt(x) {
    for (var k = 0; k < units.length; k++) if (x >= units[k].x0 - 0.5 && x < units[k].x1 + 0.5) return units[k];
    return null;
  }
  function setRange(t0, t1) {
    var minSpan = END / NC * 2;
    if (t1 - t0 < minSpan) { var m = (t0 + t1) / 2; t0 = m - minSpan / 2; t1 = m + minSpan / 2; }
    if (t1 - t0 > END) { t0 = 0; t1 = END; }
    if (t0 < 0) { t1 -= t0; t0 = 0; }
    if (t1 > END) { t0 -= t1 - END; t1 = END; }
    view.t0 = Math.max(0, t0); view.t1 = t1; drawSpeed();
  }
  (function () {
    var cv = el('speed'), drag = null;
    function tAt(x) { var pw = cv.clientWidth - SM.left - SM.right; return view.t0 + (x - SM.left) / pw * (view.t1 - view.t0); }
    cv.addEventListener('wheel', function (e) {
      e.preventDefault();
      var t = tAt(e.offsetX), f = e.deltaY < 0 ? 1 / 1.25 : 1.25;
      setRange(t - (t - view.t0) * f, t + (view.t1 - t) * f);
    }, {passive: false});
    cv.addEventListener('mousedown', function (e) { drag = {x: e.clientX, t0: view.t0, t1: view.t1, moved: false}; });
    window.addEventListener('mousemove', function (e) {
      if (!drag) return;
      var pw = cv.clientWidth - SM.left - SM.right, dt = (e.clientX - drag.x) / pw * (drag.t1 - drag.t0);
      if (Math.abs(e.clientX - drag.x) > 2) drag.moved = true;
      if (drag.moved) setRange(drag.t0 - dt, drag.t1 - dt);
    });
    window.addEventListener('mouseup', function (e) {
      if (drag && !drag.moved && e.target === cv) {
        var u = unitAt(e.offsetX);
        if (u && u.r && u.r.line >= 0) select(u.r.line);
      }
      drag = null;
    });
    cv.addEventListener('mousemove', function (e) {
      if (drag) return;
      var u = unitAt(e.offsetX);
      if (!u || !u.r || u.r.hi < 0) { showTip(0, 0, null); return; }
      var t = tAt(e.offsetX), txt = hms(t) + ' (' + fmt(t) + ' s): ' + fmt(u.r.lo) + (u.r.hi > u.r.lo ? '–' + fmt(u.r.hi) : '') +
        ' mm/min, limited by ' + (u.r.limit >= 0 ? D.limits[u.r.limit].replace('_', ' ') : '?') +
        (u.r.top >= 0 && u.r.top !== u.r.limit ? ' (the peak by ' + D.limits[u.r.top].replace('_', ' ') + ')' : '');
      if (u.n && u.n.hi >= 0) txt += '; ' + NOM.label + ' ' + fmt(u.n.hi);
      showTip(e.pageX, e.pageY, txt + '\n' + describe(u.r.line));
    });
    cv.addEventListener('mouseleave', function () { showTip(0, 0, null); });
    cv.addEventListener('dblclick', function () { setRange(0, END); });
    el('speed-reset').addEventListener('click', function () { setRange(0, END); });
  })();

  // ---- tool path ---------------------------------------------------------------------
  var P = D.path, NV = P.n || 0, QV, FL, TL, LN, PT = new Float64Array(NV * 3);
  if (NV) {
    QV = dec(P.q, Uint16Array); FL = dec(P.flags, Uint8Array); TL = dec(P.tool, Uint8Array); LN = dec(P.line, Int32Array);
    for (var i = 0; i < NV * 3; i++) { var a = i % 3; PT[i] = P.lo[a] + QV[i] / 65535 * Math.max(P.hi[a] - P.lo[a], 1e-6); }
  }
  var LO = P.lo || [0, 0, 0], HI = P.hi || [1, 1, 1], CEN = [0, 1, 2].map(function (a) { return (LO[a] + HI[a]) / 2; });
  var DIAG = Math.max(Math.hypot(HI[0] - LO[0], HI[1] - LO[1], HI[2] - LO[2]), 1e-3);
  var VIEWS = {
    xy: {axes: [0, 1], names: ['X', 'Y']}, xz: {axes: [0, 2], names: ['X', 'Z']},
    yz: {axes: [1, 2], names: ['Y', 'Z']}, iso: {yaw: -0.6, pitch: 1.0}
  };
  Object.keys(VIEWS).forEach(function (k) { var v = VIEWS[k]; v.zoom = 1; v.px = 0; v.py = 0; v.canvas = el('view-' + k); });
  function projector(name) {
    var v = VIEWS[name], w = v.canvas.clientWidth, h = v.canvas.clientHeight, m = 36;
    if (v.axes) {
      var a = v.axes[0], b = v.axes[1], sa = Math.max(HI[a] - LO[a], DIAG * 1e-3), sb = Math.max(HI[b] - LO[b], DIAG * 1e-3);
      var s = Math.min((w - 2 * m) / sa, (h - 2 * m) / sb) * v.zoom;
      return function (x, y, z) {
        var p = [x, y, z];
        return [w / 2 + v.px + (p[a] - CEN[a]) * s, h / 2 + v.py - (p[b] - CEN[b]) * s];
      };
    }
    var cy = Math.cos(v.yaw), sy = Math.sin(v.yaw), cp = Math.cos(v.pitch), sp = Math.sin(v.pitch);
    var s3 = Math.min(w, h) / DIAG * 0.85 * v.zoom;
    return function (x, y, z) {
      var dx = x - CEN[0], dy = y - CEN[1], dz = z - CEN[2];
      var rx = cy * dx - sy * dy, ry = sy * dx + cy * dy;
      var sx = rx, syy = cp * dz + sp * ry;  // pitch tips the XY plane towards the viewer
      return [w / 2 + v.px + sx * s3, h / 2 + v.py - syy * s3];
    };
  }
  function styleOf(i) { return (FL[i] & 2) ? -1 : TL[i]; }
  function strokeStyle(ctx, s) {
    if (s < 0) { ctx.strokeStyle = COL.rapid; ctx.setLineDash([6, 4]); ctx.lineWidth = 1.2; }
    else { ctx.strokeStyle = COL.tools[s % COL.tools.length]; ctx.setLineDash([]); ctx.lineWidth = 1.4; }
  }
  function drawView(name) {
    var v = VIEWS[name], g = setup(v.canvas), ctx = g.ctx, pr = projector(name);
    var sx = new Float64Array(NV), sy = new Float64Array(NV);
    for (var i = 0; i < NV; i++) { var q = pr(PT[3 * i], PT[3 * i + 1], PT[3 * i + 2]); sx[i] = q[0]; sy[i] = q[1]; }
    v.sx = sx; v.sy = sy;
    frame(ctx, name, pr, g);
    var styles = (P.tools || []).map(function (_t, k) { return k; }).concat([-1]);
    styles.forEach(function (s) {
      strokeStyle(ctx, s); ctx.beginPath();
      var pen = -2;
      for (var i = 0; i + 1 < NV; i++) {
        if (!(FL[i] & 1) || styleOf(i) !== s) continue;
        if (pen !== i) ctx.moveTo(sx[i], sy[i]);
        ctx.lineTo(sx[i + 1], sy[i + 1]); pen = i + 1;
      }
      ctx.stroke();
    });
    ctx.setLineDash([]);
    ctx.strokeStyle = COL.hole; ctx.lineWidth = 1.5;
    P.holes && P.holes.forEach(function (hh) {
      var q = pr(hh[0], hh[1], hh[2]); ctx.beginPath(); ctx.arc(q[0], q[1], 3, 0, 2 * Math.PI); ctx.stroke();
    });
    if (selected !== null) {
      ctx.strokeStyle = COL.selected; ctx.lineWidth = 4; ctx.globalAlpha = 0.8; ctx.beginPath();
      for (var k = 0; k + 1 < NV; k++) if (LN[k] === selected && (FL[k] & 1)) { ctx.moveTo(sx[k], sy[k]); ctx.lineTo(sx[k + 1], sy[k + 1]); }
      ctx.stroke(); ctx.globalAlpha = 1; ctx.lineWidth = 1;
    }
  }
  function frame(ctx, name, pr, g) {
    var v = VIEWS[name];
    ctx.fillStyle = '#333'; ctx.strokeStyle = '#bbb'; ctx.setLineDash([3, 3]); ctx.lineWidth = 1;
    if (v.axes) {
      var a = v.axes[0], b = v.axes[1], p0 = [LO[0], LO[1], LO[2]], p1 = [HI[0], HI[1], HI[2]];
      var q0 = pr(p0[0], p0[1], p0[2]), q1 = pr(p1[0], p1[1], p1[2]);
      ctx.strokeRect(q0[0], q1[1], q1[0] - q0[0], q0[1] - q1[1]); ctx.setLineDash([]);
      ctx.textAlign = 'left'; ctx.fillText(fmt(LO[a]), q0[0], q0[1] + 13);
      ctx.textAlign = 'right'; ctx.fillText(fmt(HI[a]), q1[0], q0[1] + 13);
      ctx.fillText(fmt(LO[b]), q0[0] - 3, q0[1]); ctx.fillText(fmt(HI[b]), q0[0] - 3, q1[1] + 9);
      ctx.textAlign = 'left'; ctx.fillText(v.names[0] + ' →', 6, g.h - 6);
      ctx.save(); ctx.translate(12, 30); ctx.rotate(-Math.PI / 2); ctx.textAlign = 'right'; ctx.fillText(v.names[1] + ' →', 0, 0); ctx.restore();
      return;
    }
    var c = [[LO[0], LO[1], LO[2]], [HI[0], LO[1], LO[2]], [HI[0], HI[1], LO[2]], [LO[0], HI[1], LO[2]]];
    var top = c.map(function (p) { return [p[0], p[1], HI[2]]; });
    ctx.beginPath();
    for (var k = 0; k < 4; k++) {
      [[c[k], c[(k + 1) % 4]], [top[k], top[(k + 1) % 4]], [c[k], top[k]]].forEach(function (e) {
        var s = pr(e[0][0], e[0][1], e[0][2]), t = pr(e[1][0], e[1][1], e[1][2]); ctx.moveTo(s[0], s[1]); ctx.lineTo(t[0], t[1]);
      });
    }
    ctx.stroke(); ctx.setLineDash([]);
    var o = pr(LO[0], LO[1], LO[2]), len = DIAG * 0.12;
    [['X', [LO[0] + len, LO[1], LO[2]]], ['Y', [LO[0], LO[1] + len, LO[2]]], ['Z', [LO[0], LO[1], LO[2] + len]]].forEach(function (ax) {
      var q = pr(ax[1][0], ax[1][1], ax[1][2]); ctx.strokeStyle = '#555'; ctx.beginPath(); ctx.moveTo(o[0], o[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
      ctx.fillText(ax[0], q[0] + 3, q[1] - 3);
    });
    ctx.textAlign = 'left'; ctx.fillText('drag: rotate · shift-drag: pan · wheel: zoom · double-click: reset', 6, g.h - 6);
  }
  function drawPaths() { Object.keys(VIEWS).forEach(drawView); }
  function nearest(name, x, y) {
    var v = VIEWS[name], best = 64, bi = -1;  // within 8 px (squared)
    if (!v.sx) return -1;
    for (var i = 0; i + 1 < NV; i++) {
      if (!(FL[i] & 1)) continue;
      var ax = v.sx[i], ay = v.sy[i], bx = v.sx[i + 1], by = v.sy[i + 1], dx = bx - ax, dy = by - ay, l = dx * dx + dy * dy;
      var u = l > 0 ? Math.max(0, Math.min(1, ((x - ax) * dx + (y - ay) * dy) / l)) : 0;
      var ex = ax + u * dx - x, ey = ay + u * dy - y, d = ex * ex + ey * ey;
      if (d < best) { best = d; bi = i; }
    }
    return bi;
  }
  Object.keys(VIEWS).forEach(function (name) {
    var v = VIEWS[name], cv = v.canvas, drag = null;
    cv.addEventListener('wheel', function (e) {
      e.preventDefault();
      var f = e.deltaY < 0 ? 1.25 : 1 / 1.25, w = cv.clientWidth, h = cv.clientHeight;
      v.px = (v.px - (e.offsetX - w / 2)) * f + (e.offsetX - w / 2); v.py = (v.py - (e.offsetY - h / 2)) * f + (e.offsetY - h / 2);
      v.zoom *= f; drawView(name);
    }, {passive: false});
    cv.addEventListener('mousedown', function (e) { drag = {x: e.clientX, y: e.clientY, px: v.px, py: v.py, yaw: v.yaw, pitch: v.pitch, moved: false, shift: e.shiftKey}; });
    window.addEventListener('mousemove', function (e) {
      if (!drag) return;
      var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
      if (!drag.moved) return;
      if (v.axes || drag.shift) { v.px = drag.px + dx; v.py = drag.py + dy; }
      else { v.yaw = drag.yaw + dx * 0.01; v.pitch = Math.max(0, Math.min(Math.PI, drag.pitch + dy * 0.01)); }
      drawView(name);
    });
    window.addEventListener('mouseup', function (e) {
      if (drag && !drag.moved && e.target === cv) {
        var i = nearest(name, e.offsetX, e.offsetY);
        select(i >= 0 ? LN[i] : null);
      }
      drag = null;
    });
    cv.addEventListener('mousemove', function (e) {
      if (drag) return;
      var i = nearest(name, e.offsetX, e.offsetY);
      showTip(e.pageX, e.pageY, i < 0 ? null : ((FL[i] & 2) ? 'rapid' : 'T' + P.tools[TL[i]]) + ' · ' + describe(LN[i]));
    });
    cv.addEventListener('mouseleave', function () { showTip(0, 0, null); });
    cv.addEventListener('dblclick', function () { v.zoom = 1; v.px = v.py = 0; if (!v.axes) { v.yaw = -0.6; v.pitch = 1.0; } drawView(name); });
  });

  // ---- tables ------------------------------------------------------------------------
  function key(td) { var v = td.getAttribute('data-v'); return v === null ? td.textContent : parseFloat(v); }
  document.querySelectorAll('table.sortable').forEach(function (tbl) {
    tbl.querySelectorAll('th').forEach(function (th, col) {
      th.addEventListener('click', function () {
        var body = tbl.tBodies[0], rows = Array.prototype.slice.call(body.rows);
        var dir = th.getAttribute('data-dir') === 'asc' ? -1 : 1; th.setAttribute('data-dir', dir > 0 ? 'asc' : 'desc');
        rows.sort(function (a, b) { var x = key(a.cells[col]), y = key(b.cells[col]); return x < y ? -dir : x > y ? dir : 0; });
        rows.forEach(function (r) { body.appendChild(r); });
      });
    });
  });
  document.querySelectorAll('tr[data-i]').forEach(function (tr) {
    tr.addEventListener('click', function () {
      var i = parseInt(tr.getAttribute('data-i'), 10), t0 = parseFloat(tr.getAttribute('data-t0')), t1 = parseFloat(tr.getAttribute('data-t1'));
      select(i);
      if (t1 > t0) { var pad = Math.max((t1 - t0) * 0.5, END / NC * 8); setRange(t0 - pad, t1 + pad); }
      el('speed').scrollIntoView({block: 'center'});
    });
  });

  window.addEventListener('resize', function () { drawSpeed(); drawPaths(); });
  drawSpeed(); drawPaths(); select(null);
  window.cnccTiming = {
    speedRange: function () { return [view.t0, view.t1]; },
    setSpeedRange: setRange,
    shownSpeedMax: function () { var m = -1; units.forEach(function (u) { if (u.r && u.r.hi > m) m = u.r.hi; }); return m; },
    project: function (name, x, y, z) {
      var r = VIEWS[name].canvas.getBoundingClientRect(), q = projector(name)(x, y, z);
      return [r.left + window.scrollX + q[0], r.top + window.scrollY + q[1]];
    },
    speedPoint: function (t) {  // page coordinates of time t on the speed chart (mid-height)
      var cv = el('speed'), r = cv.getBoundingClientRect(), pw = cv.clientWidth - SM.left - SM.right;
      return [r.left + window.scrollX + SM.left + (t - view.t0) / (view.t1 - view.t0) * pw,
              r.top + window.scrollY + SM.top + (cv.clientHeight - SM.top - SM.bottom) / 2];
    },
    select: select,
    selected: function () { return selected === null ? null : LINES[selected] || {i: selected}; },
    vertices: NV
  };
  document.body.setAttribute('data-ready', '1');
})();
