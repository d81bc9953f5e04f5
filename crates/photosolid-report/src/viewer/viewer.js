// photosolid's interactive view of photometric solids (src/report/viewer/mod.rs writes the data).
// The project's own small WebGL 1 code, no library and no network: the report is one HTML file that
// works from a USB stick. Each section.psv element holds its JSON data; the meshes are base64 binary
// on a regular (C, gamma) grid (vertex ic * ng + ig), so the triangles are implied by the grid.
// The vertex directions come with the data (computed in Rust in the luminaire frame: C0 = +x, C90 = +y,
// nadir = -z), so this file never converts angles to directions; the camera's up axis is +z.
(function () {
  'use strict';
  if (window.photosolidViewer) { window.photosolidViewer.initAll(); return; }

  function b64bytes(s) {
    const bin = atob(s);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out;
  }
  // Little-endian reads through a DataView: the data's byte order does not depend on the machine's.
  function readU16(bytes) {
    const dv = new DataView(bytes.buffer), n = bytes.length >> 1, out = new Float32Array(n);
    for (let i = 0; i < n; i++) out[i] = dv.getUint16(2 * i, true);
    return out;
  }
  function readI16(bytes) {
    const dv = new DataView(bytes.buffer), n = bytes.length >> 1, out = new Float32Array(n);
    for (let i = 0; i < n; i++) out[i] = dv.getInt16(2 * i, true);
    return out;
  }

  // 4x4 matrices, column-major as WebGL expects.
  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
  }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function norm(a) { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function lookAt(eye, target, up) {
    const z = norm(sub(eye, target)), x = norm(cross(up, z)), y = cross(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }
  function mul(a, b) {
    const o = new Array(16).fill(0);
    for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) o[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    return o;
  }
  function project(m, p) {
    const x = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12], y = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
    const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    return [x / w, y / w, w];
  }

  const VS = 'attribute vec3 aPos; attribute vec3 aNor; attribute vec3 aCol; uniform mat4 uMvp; uniform float uScale;' +
    'varying vec3 vN; varying vec3 vC; void main() { gl_Position = uMvp * vec4(aPos * uScale, 1.0); vN = aNor; vC = aCol; }';
  // Two-sided headlight shading: |n . l| so inner faces seen through a cut-off are lit too.
  const FS = 'precision mediump float; varying vec3 vN; varying vec3 vC; uniform vec3 uLight; uniform float uLit;' +
    'void main() { float d = abs(dot(normalize(vN + vec3(1e-6)), uLight));' +
    'gl_FragColor = vec4(vC * mix(1.0, 0.35 + 0.65 * d, uLit), 1.0); }';

  function program(gl) {
    const p = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, VS], [gl.FRAGMENT_SHADER, FS]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error('shader: ' + gl.getShaderInfoLog(s));
      gl.attachShader(p, s);
    }
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error('program: ' + gl.getProgramInfoLog(p));
    return p;
  }

  function buffer(gl, target, array) {
    const b = gl.createBuffer();
    gl.bindBuffer(target, b);
    gl.bufferData(target, array, gl.STATIC_DRAW);
    return b;
  }

  function init(root) {
    if (root.dataset.psvState) return;
    root.dataset.psvState = 'loading';
    const data = JSON.parse(root.querySelector('.psv-data').textContent);
    const nc = data.nc, ng = data.ng, nv = nc * ng;
    const glCanvas = root.querySelector('.psv-gl');
    let gl = null;
    try { gl = glCanvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true }); } catch (e) { gl = null; }
    if (!gl || nv > 65535) {
      // Degrade: the message shows and the static PNGs of the report stay the figures.
      root.querySelector('.psv-nogl').hidden = false;
      root.querySelector('.psv-main').hidden = true;
      root.dataset.psvState = 'nogl';
      return;
    }

    // Decode: positions scaled to the unit ball (radius R of the data = 1), radius in % of I_max per vertex.
    const R = data.radius, lut = data.lut, dirs = readI16(b64bytes(data.directions)).map((x) => x / 32767);
    const colorAt = (pct, scale) => {
      const t = Math.min(1, Math.max(0, 0.5 + 0.5 * pct / scale)) * (lut.length - 1);
      const k = Math.min(lut.length - 2, Math.floor(t)), f = t - k;
      return [0, 1, 2].map((i) => (lut[k][i] + f * (lut[k + 1][i] - lut[k][i])) / 255);
    };
    const solids = data.solids.map((s) => {
      const q = readU16(b64bytes(s.radius)), pos = new Float32Array(3 * nv), pct = new Float32Array(nv);
      for (let v = 0; v < nv; v++) {
        const r = q[v] / 65535;
        for (let k = 0; k < 3; k++) pos[3 * v + k] = dirs[3 * v + k] * r;
        pct[v] = r * R / data.i_max * 100;
      }
      const err = s.err ? readI16(b64bytes(s.err)).map((e) => e / 32767 * data.err_max_pct) : null;
      return { name: s.name, role: s.role, color: s.color, pos, pct, err, maxErr: s.max_abs_err_pct, scale: s.scale_pct };
    });

    // Triangles of the grid (C-planes wrap at 360 degrees), and a wire mesh about every 10 degrees.
    const tri = [], wire = [];
    const at = (ic, ig) => (ic % nc) * ng + ig;
    for (let ic = 0; ic < nc; ic++) for (let ig = 0; ig + 1 < ng; ig++) {
      tri.push(at(ic, ig), at(ic + 1, ig), at(ic + 1, ig + 1), at(ic, ig), at(ic + 1, ig + 1), at(ic, ig + 1));
    }
    const sc = Math.max(1, Math.round(10 / data.c_step_deg)), sg = Math.max(1, Math.round(10 / data.gamma_step_deg));
    for (let ic = 0; ic < nc; ic += sc) for (let ig = 0; ig + 1 < ng; ig++) wire.push(at(ic, ig), at(ic, ig + 1));
    for (let ig = sg; ig + 1 < ng; ig += sg) for (let ic = 0; ic < nc; ic++) wire.push(at(ic, ig), at(ic + 1, ig));

    const prog = program(gl);
    const loc = {
      pos: gl.getAttribLocation(prog, 'aPos'), nor: gl.getAttribLocation(prog, 'aNor'), col: gl.getAttribLocation(prog, 'aCol'),
      mvp: gl.getUniformLocation(prog, 'uMvp'), scale: gl.getUniformLocation(prog, 'uScale'), light: gl.getUniformLocation(prog, 'uLight'), lit: gl.getUniformLocation(prog, 'uLit'),
    };
    const triBuf = buffer(gl, gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(tri));
    const wireBuf = buffer(gl, gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(wire));
    for (const s of solids) {
      const n = new Float32Array(3 * nv);
      for (let t = 0; t < tri.length; t += 3) {
        const [a, b, c] = [tri[t], tri[t + 1], tri[t + 2]];
        const pa = [s.pos[3 * a], s.pos[3 * a + 1], s.pos[3 * a + 2]];
        const f = cross(sub([s.pos[3 * b], s.pos[3 * b + 1], s.pos[3 * b + 2]], pa), sub([s.pos[3 * c], s.pos[3 * c + 1], s.pos[3 * c + 2]], pa));
        for (const v of [a, b, c]) for (let k = 0; k < 3; k++) n[3 * v + k] += f[k];
      }
      // The pole rows are one point each, repeated per C-plane: give them one shared normal.
      for (const ig of [0, ng - 1]) {
        const m = [0, 0, 0];
        for (let ic = 0; ic < nc; ic++) for (let k = 0; k < 3; k++) m[k] += n[3 * at(ic, ig) + k];
        for (let ic = 0; ic < nc; ic++) for (let k = 0; k < 3; k++) n[3 * at(ic, ig) + k] = m[k];
      }
      s.posBuf = buffer(gl, gl.ARRAY_BUFFER, s.pos);
      s.norBuf = buffer(gl, gl.ARRAY_BUFFER, n);
      s.colBuf = gl.createBuffer();
    }
    // One colour scale for the visible surfaces: the largest of their own scales (computed in Rust).
    let scale = 0;
    function recolour() {
      const want = Math.max(0, ...solids.filter((s, i) => state.visible[i] && s.err).map((s) => s.scale)) || 1;
      if (want === scale) return;
      scale = want;
      for (const s of solids) {
        if (!s.err) continue;
        const col = new Float32Array(3 * nv);
        for (let v = 0; v < nv; v++) col.set(colorAt(s.err[v], scale), 3 * v);
        gl.bindBuffer(gl.ARRAY_BUFFER, s.colBuf);
        gl.bufferData(gl.ARRAY_BUFFER, col, gl.STATIC_DRAW);
      }
      drawScale();
    }
    // The luminaire frame: C0 (+x), C90 (+y), nadir (-z), drawn to 1.25 R.
    const axes = [{ to: [1.25, 0, 0], label: 'C0', color: [0.8, 0.1, 0.1] }, { to: [0, 1.25, 0], label: 'C90', color: [0.1, 0.55, 0.1] },
      { to: [0, 0, -1.25], label: 'nadir (\u03b3 = 0)', color: [0.1, 0.2, 0.8] }];
    const axisBuf = buffer(gl, gl.ARRAY_BUFFER, new Float32Array(axes.flatMap((a) => [0, 0, 0].concat(a.to))));
    const planeBuf = gl.createBuffer();

    const state = { yaw: -0.9, pitch: 0.35, dist: 3.0, target: [0, 0, 0], c: 0, visible: solids.map((s, i) => i <= 1) };
    const toggles = root.querySelector('.psv-toggles');
    solids.forEach((s, i) => {
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = state.visible[i];
      box.dataset.solid = s.name;
      box.addEventListener('change', () => { state.visible[i] = box.checked; draw(); });
      const sw = document.createElement('span');
      sw.className = 'psv-swatch';
      sw.style.background = s.color;
      label.append(box, sw, document.createTextNode(s.role === 'reference' ? 'reference (wire)' :
        s.name + ' (' + data.legend_quantity + ' ' + s.maxErr.toPrecision(3) + ' %)'));
      toggles.append(label);
    });
    const slider = root.querySelector('.psv-c'), cval = root.querySelector('.psv-cval');
    slider.addEventListener('input', () => { state.c = Number(slider.value); draw(); });

    // The radius (% of I_max) and position at (c, gamma index) by linear interpolation between C-planes.
    function sampleAt(s, c, ig) {
      const x = ((c % 360) + 360) % 360 / data.c_step_deg, i0 = Math.floor(x) % nc, i1 = (i0 + 1) % nc, f = x - Math.floor(x);
      const a = i0 * ng + ig, b = i1 * ng + ig;
      return { pct: (1 - f) * s.pct[a] + f * s.pct[b], p: [0, 1, 2].map((k) => (1 - f) * s.pos[3 * a + k] + f * s.pos[3 * b + k]) };
    }

    const labels = root.querySelector('.psv-labels'), lctx = labels.getContext('2d');
    function draw() {
      recolour();
      const w = glCanvas.width, h = glCanvas.height;
      gl.viewport(0, 0, w, h);
      gl.clearColor(1, 1, 1, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.useProgram(prog);
      const cp = Math.cos(state.pitch), eyeDir = [cp * Math.cos(state.yaw), cp * Math.sin(state.yaw), Math.sin(state.pitch)];
      const eye = state.target.map((t, k) => t + state.dist * eyeDir[k]);
      const mvp = mul(perspective(0.7, w / h, 0.05, 50), lookAt(eye, state.target, [0, 0, 1]));
      gl.uniformMatrix4fv(loc.mvp, false, new Float32Array(mvp));
      gl.uniform3fv(loc.light, new Float32Array(eyeDir));
      const attr = (l, buf) => { gl.bindBuffer(gl.ARRAY_BUFFER, buf); gl.enableVertexAttribArray(l); gl.vertexAttribPointer(l, 3, gl.FLOAT, false, 0, 0); };
      const constant = (l, v) => { gl.disableVertexAttribArray(l); gl.vertexAttrib3f(l, v[0], v[1], v[2]); };
      // With no reconstruction shown the reference is a grey shaded surface under its wire mesh, the wire
      // drawn 0.3 % outside so that it stays in front (glPolygonOffset renders differently from frame to
      // frame on SwiftShader, the browser tests' software WebGL).
      const anyRecon = solids.some((s, i) => state.visible[i] && s.err);
      gl.uniform1f(loc.scale, 1);
      solids.forEach((s, i) => {
        if (!state.visible[i]) return;
        attr(loc.pos, s.posBuf);
        if (s.err || !anyRecon) {
          attr(loc.nor, s.norBuf); gl.uniform1f(loc.lit, 1);
          if (s.err) attr(loc.col, s.colBuf); else constant(loc.col, [0.8, 0.8, 0.8]);
          gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, triBuf);
          gl.drawElements(gl.TRIANGLES, tri.length, gl.UNSIGNED_SHORT, 0);
        }
        if (!s.err) {
          constant(loc.nor, [0, 0, 1]); constant(loc.col, [0.1, 0.1, 0.1]); gl.uniform1f(loc.lit, 0);
          gl.uniform1f(loc.scale, anyRecon ? 1 : 1.003);
          gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, wireBuf);
          gl.drawElements(gl.LINES, wire.length, gl.UNSIGNED_SHORT, 0);
          gl.uniform1f(loc.scale, 1);
        }
      });
      // The chosen C-plane: the reference's curve in it, a little outside the solid.
      const plane = [];
      for (const c of [state.c, state.c + 180]) for (let ig = 0; ig < ng; ig++) plane.push(...sampleAt(solids[0], c, ig).p.map((x) => x * 1.01));
      gl.bindBuffer(gl.ARRAY_BUFFER, planeBuf);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(plane), gl.DYNAMIC_DRAW);
      attr(loc.pos, planeBuf); constant(loc.nor, [0, 0, 1]); constant(loc.col, [0.95, 0.55, 0.0]); gl.uniform1f(loc.lit, 0);
      gl.drawArrays(gl.LINE_STRIP, 0, ng);
      gl.drawArrays(gl.LINE_STRIP, ng, ng);
      attr(loc.pos, axisBuf);
      axes.forEach((a, k) => { constant(loc.col, a.color); gl.drawArrays(gl.LINES, 2 * k, 2); });
      // Axis labels on the 2D overlay, at the projected axis tips.
      lctx.clearRect(0, 0, labels.width, labels.height);
      lctx.font = Math.round(14 * labels.width / glCanvas.clientWidth || 14) + 'px sans-serif';
      axes.forEach((a) => {
        const q = project(mvp, a.to.map((x) => x * 1.04));
        if (q[2] <= 0) return;
        lctx.fillStyle = 'rgb(' + a.color.map((x) => Math.round(x * 255)).join(',') + ')';
        lctx.fillText(a.label, (q[0] * 0.5 + 0.5) * labels.width, (0.5 - q[1] * 0.5) * labels.height);
      });
      drawPolar();
      root.dataset.psvState = 'ready';
    }

    const polar = root.querySelector('.psv-polar'), pctx = polar.getContext('2d');
    function drawPolar() {
      const c = state.c, w = polar.width, h = polar.height, cx = w / 2, cy = h / 2 - 4, rad = Math.min(w, h) / 2 - 22;
      cval.textContent = 'C' + c + ' \u2013 C' + (c + 180);
      const curves = solids.filter((s, i) => state.visible[i]).map((s) => ({ s, right: [], left: [] }));
      let top = 0;
      for (const k of curves) for (let ig = 0; ig < ng; ig++) {
        k.right.push(sampleAt(k.s, c, ig).pct); k.left.push(sampleAt(k.s, c + 180, ig).pct);
        top = Math.max(top, k.right[ig], k.left[ig]);
      }
      const step = [5, 10, 25, 50, 100].find((x) => top <= 4 * x) || Math.ceil(top / 400) * 100, full = 4 * step;
      pctx.clearRect(0, 0, w, h);
      pctx.fillStyle = '#fff'; pctx.fillRect(0, 0, w, h);
      pctx.strokeStyle = '#ccc'; pctx.fillStyle = '#666'; pctx.font = '11px sans-serif'; pctx.lineWidth = 1;
      for (let k = 1; k <= 4; k++) {
        pctx.beginPath(); pctx.arc(cx, cy, rad * k / 4, 0, 2 * Math.PI); pctx.stroke();
        pctx.fillText(k * step + ' %', cx + 3, cy - rad * k / 4 - 2);
      }
      pctx.beginPath(); pctx.moveTo(cx - rad, cy); pctx.lineTo(cx + rad, cy); pctx.moveTo(cx, cy - rad); pctx.lineTo(cx, cy + rad); pctx.stroke();
      pctx.fillText('C' + (c + 180), 4, 12); pctx.fillText('C' + c, w - 40, 12);
      pctx.fillText('\u03b3 = 0 (nadir)', cx + 4, h - 4);
      for (const k of curves) {
        // Gamma 0 points down (nadir); the plane C to the right, C + 180 to the left.
        pctx.beginPath();
        pctx.strokeStyle = k.s.color; pctx.lineWidth = k.s.err ? 1.6 : 1.2;
        pctx.setLineDash(k.s.err ? [] : [5, 3]);
        for (let ig = ng - 1; ig >= 0; ig--) {
          const g = ig * data.gamma_step_deg * Math.PI / 180, r = rad * k.left[ig] / full;
          pctx[ig === ng - 1 ? 'moveTo' : 'lineTo'](cx - r * Math.sin(g), cy + r * Math.cos(g));
        }
        for (let ig = 0; ig < ng; ig++) {
          const g = ig * data.gamma_step_deg * Math.PI / 180, r = rad * k.right[ig] / full;
          pctx.lineTo(cx + r * Math.sin(g), cy + r * Math.cos(g));
        }
        pctx.stroke();
      }
      pctx.setLineDash([]);
      pctx.fillStyle = '#222';
      pctx.fillText('% of I_max', 4, h - 4);
    }

    // The colour scale, labelled in % of I_max.
    function drawScale() {
      const cv = root.querySelector('.psv-scale'), x = cv.getContext('2d'), w = cv.width, m = 26;
      x.clearRect(0, 0, w, cv.height);
      for (let i = 0; i < w - 2 * m; i++) {
        const col = colorAt((2 * i / (w - 2 * m - 1) - 1) * scale, scale).map((v) => Math.round(v * 255));
        x.fillStyle = 'rgb(' + col.join(',') + ')';
        x.fillRect(m + i, 4, 1, 16);
      }
      x.fillStyle = '#222'; x.font = '11px sans-serif'; x.textAlign = 'center';
      for (const f of [-1, -0.5, 0, 0.5, 1]) {
        const v = f * scale;
        x.fillText((v > 0 ? '+' : '') + Number(v.toPrecision(3)) + ' %', m + (f + 1) / 2 * (w - 2 * m), 34);
      }
      x.fillText('reconstruction \u2212 reference, % of I_max', w / 2, 50);
    }

    // Orbit (one pointer), pan (shift, right button, or two pointers), zoom (wheel or pinch): pointer events
    // serve mouse, pen and touch alike; touch-action: none in the CSS keeps the page from scrolling instead.
    const pointers = new Map();
    let pinch = null;
    // Capture keeps a drag alive outside the canvas; a pointer the browser does not track (a synthetic event)
    // cannot be captured, and the drag still works without it.
    glCanvas.addEventListener('pointerdown', (e) => { try { glCanvas.setPointerCapture(e.pointerId); } catch (err) { /* see above */ } pointers.set(e.pointerId, [e.clientX, e.clientY]); pinch = null; });
    const up = (e) => { pointers.delete(e.pointerId); pinch = null; };
    glCanvas.addEventListener('pointerup', up);
    glCanvas.addEventListener('pointercancel', up);
    glCanvas.addEventListener('contextmenu', (e) => e.preventDefault());
    function pan(dx, dy) {
      const s = state.dist / glCanvas.clientHeight, right = [-Math.sin(state.yaw), Math.cos(state.yaw), 0];
      const upv = cross(norm([Math.cos(state.yaw), Math.sin(state.yaw), Math.tan(state.pitch)]), right);
      state.target = state.target.map((t, k) => t - s * (dx * right[k] - dy * upv[k]));
    }
    glCanvas.addEventListener('pointermove', (e) => {
      const last = pointers.get(e.pointerId);
      if (!last) return;
      const dx = e.clientX - last[0], dy = e.clientY - last[1];
      pointers.set(e.pointerId, [e.clientX, e.clientY]);
      if (pointers.size === 2) {
        const [a, b] = [...pointers.values()], d = Math.hypot(a[0] - b[0], a[1] - b[1]), mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
        if (pinch) { state.dist = Math.min(20, Math.max(0.5, state.dist * pinch.d / Math.max(d, 1))); pan(mid[0] - pinch.mid[0], mid[1] - pinch.mid[1]); }
        pinch = { d, mid };
      } else if (e.shiftKey || (e.buttons & 2)) {
        pan(dx, dy);
      } else {
        state.yaw -= dx * 0.01;
        state.pitch = Math.min(1.55, Math.max(-1.55, state.pitch + dy * 0.01));
      }
      draw();
    });
    glCanvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      state.dist = Math.min(20, Math.max(0.5, state.dist * Math.exp(e.deltaY * 0.001)));
      draw();
    }, { passive: false });

    // Keep the drawing buffer at the displayed size (sharp on high-density screens).
    function fit() {
      const dpr = window.devicePixelRatio || 1, w = Math.max(1, Math.round(glCanvas.clientWidth * dpr)), h = Math.max(1, Math.round(glCanvas.clientHeight * dpr));
      if (w !== glCanvas.width || h !== glCanvas.height) { glCanvas.width = labels.width = w; glCanvas.height = labels.height = h; }
      draw();
    }
    if (window.ResizeObserver) new ResizeObserver(fit).observe(glCanvas); else fit();
    fit();
  }

  function initAll() {
    for (const root of document.querySelectorAll('section.psv')) {
      try { init(root); } catch (e) {
        const msg = root.querySelector('.psv-nogl');
        msg.hidden = false;
        msg.textContent = 'The interactive view failed (' + e.message + '); the static figures show the same data.';
        root.dataset.psvState = 'error';
        throw e;
      }
    }
  }
  window.photosolidViewer = { initAll };
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', initAll); else initAll();
})();
