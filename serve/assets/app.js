// rtprof serve: the page's script. Vanilla ES2020, no dependencies, no network
// reference outside this server. Every piece of data is inserted as text
// (textContent / createElement), never as HTML.
'use strict';

(() => {
  // ---------------------------------------------------------------- constants

  const FINAL = new Set(['done', 'failed', 'cancelled', 'interrupted']);
  const ACTIVE = new Set(['queued', 'running']);
  const TABS = ['pick', 'run', 'view', 'open', 'gate'];
  const GROUPS = [['builtin', 'built-in'], ['uploaded', 'uploaded']];
  const POLL_MS = 4000;
  const COMPARE_WIDTH = 640; // target on-screen width of the comparison slider

  const token = document.querySelector('meta[name="rtprof-token"]')?.getAttribute('content') ?? '';
  const intFormat = new Intl.NumberFormat('en-US', { maximumFractionDigits: 0 });

  const state = {
    catalog: null, // GET /api/scenes
    generated: [], // generated scene ids chosen in this session
    chosenScene: null,
    jobs: [], // newest first
    selectedId: null,
    follow: null, // { id, source } the EventSource of the followed job
    results: new Map(), // job id -> results.json (finished jobs do not change)
    viewKey: null, // what the results area shows: `${id}:${status}`
    tab: 'pick',
    refreshing: null,
    refreshAgain: false,
  };

  // ---------------------------------------------------------------- helpers

  const $ = (id) => document.getElementById(id);

  /** Creates an element; attributes are set as attributes, children as text or nodes. */
  function el(tag, attrs = {}, ...children) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attrs)) {
      if (value == null || value === false) continue;
      if (key === 'class') node.className = value;
      else if (key === 'text') node.textContent = String(value);
      else if (key === 'style' && typeof value === 'object') Object.assign(node.style, value);
      else if (key.startsWith('on') && typeof value === 'function') node.addEventListener(key.slice(2), value);
      else if (value === true) node.setAttribute(key, '');
      else node.setAttribute(key, String(value));
    }
    for (const child of children.flat(Infinity)) {
      if (child == null || child === false) continue;
      node.append(child instanceof Node ? child : String(child));
    }
    return node;
  }

  /** A safe class-name fragment from data. */
  const cssPart = (s) => String(s ?? '').toLowerCase().replace(/[^a-z0-9_-]/g, '_');

  const isNum = (x) => typeof x === 'number' && Number.isFinite(x);

  function fmtInt(n) {
    return isNum(n) ? intFormat.format(n) : '—';
  }

  function fmtFixed(x, digits) {
    if (!isNum(x)) return '—';
    return new Intl.NumberFormat('en-US', {
      minimumFractionDigits: digits,
      maximumFractionDigits: digits,
    }).format(x);
  }

  /** Seconds as milliseconds, with precision that suits the size. */
  function fmtMs(seconds) {
    if (!isNum(seconds)) return '—';
    const ms = seconds * 1000;
    const digits = ms < 1 ? 3 : ms < 10 ? 2 : ms < 100 ? 1 : 0;
    return `${fmtFixed(ms, digits)} ms`;
  }

  function fmtSeconds(seconds) {
    if (!isNum(seconds)) return '—';
    return fmtFixed(seconds, seconds < 0.1 ? 4 : 3);
  }

  function fmtSpeedup(x) {
    return isNum(x) ? `${fmtFixed(x, 2)}×` : '—';
  }

  function fmtMean(x) {
    if (!isNum(x)) return '—';
    return fmtFixed(x, Math.abs(x) >= 100 ? 1 : 2);
  }

  function fmtTime(iso) {
    if (!iso) return '—';
    const d = new Date(iso);
    if (Number.isNaN(d.getTime())) return String(iso);
    const now = new Date();
    const sameDay = d.toDateString() === now.toDateString();
    return sameDay
      ? d.toLocaleTimeString(undefined, { hour: '2-digit', minute: '2-digit', second: '2-digit' })
      : d.toLocaleString(undefined, { year: 'numeric', month: 'short', day: 'numeric', hour: '2-digit', minute: '2-digit' });
  }

  function fmtDuration(fromIso, toIso) {
    const a = Date.parse(fromIso);
    const b = toIso ? Date.parse(toIso) : Date.now();
    if (!Number.isFinite(a) || !Number.isFinite(b) || b < a) return null;
    const s = Math.round((b - a) / 1000);
    if (s < 60) return `${s} s`;
    const m = Math.floor(s / 60);
    if (m < 60) return `${m} min ${s % 60} s`;
    return `${Math.floor(m / 60)} h ${m % 60} min`;
  }

  /** The URL of a job's file; each path segment is encoded. */
  function fileUrl(jobId, path) {
    const segments = String(path).split('/').filter((s) => s !== '' && s !== '.' && s !== '..');
    return `/api/jobs/${encodeURIComponent(jobId)}/files/${segments.map(encodeURIComponent).join('/')}`;
  }

  function joinPath(dir, name) {
    if (!dir) return name;
    return `${String(dir).replace(/\/+$/, '')}/${name}`;
  }

  /** The band's name and RMS range, as GET /api/scenes gives them (the thesis's table 2). */
  function bandInfo(band) {
    return (state.catalog?.bands ?? []).find((b) => b.key === band) ?? null;
  }

  function bandName(band) {
    return bandInfo(band)?.name ?? String(band).replace(/_/g, ' ');
  }

  function bandTitle(band) {
    const bands = state.catalog?.bands ?? [];
    const i = bands.findIndex((b) => b.key === band);
    if (i < 0) return `RMS band: ${bandName(band)}`;
    const low = i === 0 ? 0 : bands[i - 1].upper_edge;
    const high = bands[i].upper_edge;
    const range = high == null ? `RMS ≥ ${low}` : `${low} ≤ RMS < ${high}`;
    return `RMS band: ${bands[i].name} (${range}; thesis table 2)`;
  }

  function bandChip(band) {
    if (!band) return null;
    return el('span', { class: `band band-${cssPart(band)}`, title: bandTitle(band) },
      bandName(band));
  }

  function statusBadge(status) {
    return el('span', { class: `badge status-${cssPart(status)}` }, String(status ?? 'unknown'));
  }

  function jobScene(job) {
    const req = job?.request ?? {};
    const run = Array.isArray(req.run) ? req.run : [];
    if (run.includes('suite')) return 'quick suite';
    return req.scene ?? '—';
  }

  function jobVariants(job) {
    const req = job?.request ?? {};
    const run = Array.isArray(req.run) ? req.run : [];
    if (run.includes('suite')) return 'all variants';
    const v = Array.isArray(req.variants) ? req.variants : [];
    return v.length ? v.join(', ') : 'baseline';
  }

  function jobById(id) {
    return state.jobs.find((j) => j.id === id) ?? null;
  }

  // ---------------------------------------------------------------- API

  class ApiError extends Error {
    constructor(message, status, body) {
      super(message);
      this.status = status;
      this.body = body;
    }
  }

  /**
   * Calls the API. `body` is sent as JSON unless `contentType` is given (then as is).
   * POST and DELETE carry the token. Resolves with the parsed JSON (or null);
   * rejects with an ApiError carrying the server's `error` message.
   */
  async function api(method, url, { body, contentType } = {}) {
    const headers = { Accept: 'application/json' };
    const init = { method, headers, credentials: 'same-origin', cache: 'no-store' };
    if (method !== 'GET' && method !== 'HEAD') headers['X-Rtprof-Token'] = token;
    if (body !== undefined) {
      if (contentType) {
        headers['Content-Type'] = contentType;
        init.body = body;
      } else {
        headers['Content-Type'] = 'application/json';
        init.body = JSON.stringify(body);
      }
    }
    let response;
    try {
      response = await fetch(url, init);
    } catch (err) {
      throw new ApiError(`cannot reach the rtprof server (${err.message})`, 0, null);
    }
    const text = await response.text();
    let data = null;
    if (text) {
      try {
        data = JSON.parse(text);
      } catch (_) {
        data = null;
      }
    }
    if (!response.ok) {
      const message = data && typeof data.error === 'string'
        ? data.error
        : `${method} ${url}: HTTP ${response.status} ${response.statusText}`.trim();
      throw new ApiError(message, response.status, data);
    }
    return data;
  }

  // ---------------------------------------------------------------- messages

  let messageTimer = null;

  function clearMessage() {
    const box = $('message');
    box.hidden = true;
    box.replaceChildren();
  }

  /** Shows a message in the status area; errors stay until dismissed. */
  function showMessage(text, kind = 'error') {
    const box = $('message');
    box.className = `message message-${kind}`;
    box.replaceChildren(
      el('span', { class: 'message-text' }, text),
      el('button', { type: 'button', class: 'message-close', 'aria-label': 'Dismiss', onclick: clearMessage }, '×'),
    );
    box.hidden = false;
    clearTimeout(messageTimer);
    if (kind !== 'error') messageTimer = setTimeout(clearMessage, 6000);
  }

  function reportError(err, context) {
    const text = err instanceof Error ? err.message : String(err);
    showMessage(context ? `${context}: ${text}` : text, 'error');
    if (!(err instanceof ApiError)) console.error(err);
  }

  // ---------------------------------------------------------------- tabs

  function showTab(name, { updateHash = true, focus = false } = {}) {
    if (!TABS.includes(name)) name = 'pick';
    state.tab = name;
    for (const t of TABS) {
      const on = t === name;
      const button = $(`tab-${t}`);
      button.setAttribute('aria-selected', String(on));
      button.tabIndex = on ? 0 : -1;
      $(`panel-${t}`).hidden = !on;
      if (on && focus) button.focus();
    }
    if (updateHash) writeHash();
  }

  function writeHash() {
    const params = new URLSearchParams();
    params.set('tab', state.tab);
    if (state.selectedId) params.set('job', state.selectedId);
    history.replaceState(null, '', `#${params}`);
  }

  function readHash() {
    const p = new URLSearchParams(location.hash.slice(1));
    return { tab: p.get('tab'), job: p.get('job') };
  }

  function wireTabs() {
    const list = document.querySelector('.tabs');
    list.addEventListener('click', (ev) => {
      const button = ev.target.closest('[role="tab"]');
      if (button) showTab(button.dataset.tab);
    });
    list.addEventListener('keydown', (ev) => {
      const i = TABS.indexOf(state.tab);
      let next = null;
      if (ev.key === 'ArrowRight') next = TABS[(i + 1) % TABS.length];
      else if (ev.key === 'ArrowLeft') next = TABS[(i + TABS.length - 1) % TABS.length];
      else if (ev.key === 'Home') next = TABS[0];
      else if (ev.key === 'End') next = TABS[TABS.length - 1];
      if (next) {
        ev.preventDefault();
        showTab(next, { focus: true });
      }
    });
    document.addEventListener('click', (ev) => {
      const goto = ev.target.closest('[data-goto]');
      if (goto) showTab(goto.dataset.goto);
    });
  }

  // ---------------------------------------------------------------- Pick

  async function loadCatalog(initial) {
    const data = await api('GET', '/api/scenes');
    state.catalog = data ?? {};
    renderSceneSelect();
    if (initial) {
      renderGenerators();
      renderVariants();
      renderParts();
      applyLimits();
    }
  }

  function sceneLabel(s) {
    const bits = [s.id];
    const extra = [];
    if (s.family) extra.push(s.family);
    if (isNum(s.primitives)) extra.push(`${fmtInt(s.primitives)} primitive${s.primitives === 1 ? '' : 's'}`);
    if (extra.length) bits.push(`(${extra.join(', ')})`);
    return bits.join(' ');
  }

  function renderSceneSelect() {
    const select = $('scene');
    const scenes = state.catalog?.scenes ?? [];
    const groups = [...GROUPS];
    for (const s of scenes) {
      const g = s.group ?? 'builtin';
      if (!groups.some(([key]) => key === g)) groups.push([g, g]);
    }
    const nodes = [];
    for (const [key, label] of groups) {
      const members = scenes.filter((s) => (s.group ?? 'builtin') === key);
      const group = el('optgroup', { label });
      if (!members.length) {
        group.append(el('option', { value: '', disabled: true }, key === 'uploaded' ? '(none uploaded yet)' : '(none)'));
      }
      for (const s of members) group.append(el('option', { value: s.id }, sceneLabel(s)));
      nodes.push(group);
    }
    if (state.generated.length) {
      const group = el('optgroup', { label: 'generated' });
      for (const id of state.generated) group.append(el('option', { value: id }, id));
      nodes.push(group);
    }
    select.replaceChildren(...nodes);
    if (!state.chosenScene) {
      const first = scenes[0]?.id ?? state.generated[0] ?? null;
      if (first) chooseScene(first);
    } else {
      select.value = state.chosenScene;
    }
  }

  function chooseScene(id) {
    state.chosenScene = id;
    $('chosen-scene').textContent = id ?? 'none';
    $('run-scene').textContent = id ?? 'none';
    const select = $('scene');
    if ([...select.options].some((o) => o.value === id)) select.value = id;
  }

  function currentGenerator() {
    const gens = state.catalog?.generators ?? [];
    return gens[Number($('generator').value)] ?? null;
  }

  function renderGenerators() {
    const gens = state.catalog?.generators ?? [];
    $('generator').replaceChildren(...gens.map((g, i) => el('option', { value: String(i) }, g.label ?? g.prefix)));
    $('generator-box').hidden = gens.length === 0;
    onGeneratorChange();
  }

  function onGeneratorChange() {
    const g = currentGenerator();
    if (!g) return;
    const input = $('generator-param');
    if (isNum(g.min)) input.min = String(g.min); else input.removeAttribute('min');
    if (isNum(g.max)) input.max = String(g.max); else input.removeAttribute('max');
    input.value = String(g.default ?? g.min ?? 1);
    $('generator-param-label').textContent = g.parameter ? g.parameter[0].toUpperCase() + g.parameter.slice(1) : 'Parameter';
    $('generator-range').textContent = `${g.parameter ?? 'parameter'} ${g.min}–${g.max}, default ${g.default}.`;
    $('generator-summary').textContent = g.summary ? `Default: ${g.summary}.`.replace(/\.\.$/, '.') : '';
    updateGeneratorPreview();
  }

  function updateGeneratorPreview() {
    const g = currentGenerator();
    const button = $('generator-use');
    if (!g) return;
    const v = $('generator-param').value.trim();
    button.textContent = v ? `Use ${g.prefix}:${v}` : 'Use';
  }

  function useGenerator() {
    const g = currentGenerator();
    if (!g) return;
    const raw = $('generator-param').value.trim();
    const n = Number(raw);
    if (raw === '' || !Number.isInteger(n) || (isNum(g.min) && n < g.min) || (isNum(g.max) && n > g.max)) {
      showMessage(`${g.label ?? g.prefix}: the ${g.parameter ?? 'parameter'} must be a whole number from ${g.min} to ${g.max}.`);
      return;
    }
    const id = `${g.prefix}:${n}`;
    if (!state.generated.includes(id)) state.generated.push(id);
    state.chosenScene = id;
    renderSceneSelect();
    chooseScene(id);
    showMessage(`Scene ${id} chosen.`, 'info');
  }

  function defaultUploadName(fileName) {
    const base = String(fileName).replace(/^.*[\\/]/, '').replace(/\.[^.]*$/, '');
    const clean = base.replace(/[^A-Za-z0-9_-]+/g, '-').replace(/^-+|-+$/g, '').slice(0, 64);
    return clean || 'scene';
  }

  function showUploadError(text) {
    const box = $('upload-error');
    box.textContent = text;
    box.hidden = !text;
  }

  async function upload(ev) {
    ev.preventDefault();
    showUploadError('');
    const file = $('upload-file').files?.[0];
    if (!file) {
      showUploadError('Choose an NFF file first.');
      return;
    }
    const max = state.catalog?.limits?.max_upload_bytes;
    if (isNum(max) && file.size > max) {
      showUploadError(`The file has ${fmtInt(file.size)} bytes; the limit is ${fmtInt(max)}.`);
      return;
    }
    const name = $('upload-name').value.trim() || defaultUploadName(file.name);
    const button = $('upload-button');
    button.disabled = true;
    button.textContent = 'Uploading…';
    try {
      const text = await file.text();
      const scene = await api('POST', `/api/scenes?name=${encodeURIComponent(name)}`, {
        body: text,
        contentType: 'text/plain; charset=utf-8',
      });
      await loadCatalog(false);
      if (scene?.id) chooseScene(scene.id);
      $('upload-form').reset();
      updateUploadPlaceholder();
      const prims = isNum(scene?.primitives) ? `, ${fmtInt(scene.primitives)} primitives` : '';
      showMessage(`Uploaded ${scene?.id ?? name}${prims}; it is now the chosen scene.`, 'info');
    } catch (err) {
      if (err instanceof ApiError && [400, 413, 422].includes(err.status)) {
        const line = isNum(err.body?.line) && !String(err.message).includes(`:${err.body.line}`)
          ? ` (line ${err.body.line})` : '';
        showUploadError(`${err.message}${line}`);
      } else {
        reportError(err, 'Upload');
      }
    } finally {
      button.disabled = false;
      button.textContent = 'Upload';
    }
  }

  function updateUploadPlaceholder() {
    const file = $('upload-file').files?.[0];
    $('upload-name').placeholder = file ? defaultUploadName(file.name) : 'e.g. my-scene';
  }

  // ---------------------------------------------------------------- Run

  function renderVariants() {
    const variants = state.catalog?.variants ?? [];
    const list = $('variant-list');
    list.replaceChildren(...variants.map((v) => {
      const baseline = v.name === 'baseline';
      return el('label', { class: `check${baseline ? ' reference' : ''}` },
        el('input', { type: 'checkbox', name: 'variant', value: v.name, checked: baseline, disabled: baseline }),
        el('span', { class: 'check-body' },
          el('span', { class: 'check-name' }, v.name),
          baseline ? el('span', { class: 'tag' }, 'reference') : null,
          el('span', { class: 'check-summary' }, v.summary ?? ''),
          baseline
            ? el('span', { class: 'check-summary note-inline' }, 'Always run, first: it is the reference the others are compared with.')
            : null,
        ));
    }));
    if (!variants.length) list.replaceChildren(el('p', { class: 'muted' }, 'No variants.'));
  }

  function renderParts() {
    const parts = state.catalog?.parts ?? [];
    const list = $('part-list');
    list.replaceChildren(...parts.map((p) => el('label', { class: 'check' },
      el('input', { type: 'checkbox', name: 'part', value: p.name, checked: p.name === 'render' }),
      el('span', { class: 'check-body' },
        el('span', { class: 'check-name' }, p.name),
        el('span', { class: 'check-summary' }, p.label ?? ''),
      ))));
    if (!parts.length) list.replaceChildren(el('p', { class: 'muted' }, 'No parts.'));
    list.addEventListener('change', onPartsChange);
    onPartsChange();
  }

  function onPartsChange() {
    const suite = document.querySelector('input[name="part"][value="suite"]')?.checked ?? false;
    for (const box of document.querySelectorAll('input[name="part"]')) {
      if (box.value !== 'suite') {
        box.disabled = suite;
        box.closest('label')?.classList.toggle('disabled', suite);
      }
    }
    for (const box of document.querySelectorAll('input[name="variant"]')) {
      if (box.value !== 'baseline') box.disabled = suite;
      box.closest('label')?.classList.toggle('disabled', suite);
    }
    $('variants-all').disabled = suite;
    $('variants-none').disabled = suite;
    $('suite-note').hidden = !suite;
    $('run-scene').classList.toggle('ignored', suite);
  }

  function setAllVariants(on) {
    for (const box of document.querySelectorAll('input[name="variant"]')) {
      if (box.value !== 'baseline' && !box.disabled) box.checked = on;
    }
  }

  function applyLimits() {
    const limits = state.catalog?.limits ?? {};
    for (const id of ['width', 'height']) {
      if (isNum(limits.max_side)) $(id).max = String(limits.max_side);
    }
    const bits = ['Leave threads empty to use every core.'];
    const size = [];
    if (isNum(limits.max_side)) size.push(`each side at most ${fmtInt(limits.max_side)} pixels`);
    if (isNum(limits.max_pixels)) size.push(`at most ${fmtInt(limits.max_pixels)} pixels in all`);
    if (size.length) bits.push(`Image size: ${size.join(', ')}.`);
    $('size-hint').textContent = bits.join(' ');
    if (isNum(limits.max_upload_bytes)) {
      $('upload-limit').textContent = `Up to ${fmtSize(limits.max_upload_bytes)}.`;
    }
  }

  function fmtSize(bytes) {
    if (bytes >= 1 << 20) return `${fmtFixed(bytes / (1 << 20), 0)} MiB`;
    if (bytes >= 1 << 10) return `${fmtFixed(bytes / (1 << 10), 0)} KiB`;
    return `${fmtInt(bytes)} bytes`;
  }

  function readPositiveInt(id, label) {
    const raw = $(id).value.trim();
    const n = Number(raw);
    if (raw === '' || !Number.isInteger(n) || n < 1) throw new Error(`${label} must be a whole number of at least 1.`);
    return n;
  }

  function buildRequest() {
    const parts = [...document.querySelectorAll('input[name="part"]:checked')].map((b) => b.value);
    const suite = parts.includes('suite');
    const run = suite ? ['suite'] : parts;
    if (!run.length) throw new Error('Choose at least one part to run.');
    const scene = state.chosenScene ?? state.catalog?.scenes?.[0]?.id ?? null;
    if (!scene) throw new Error('Pick a scene first.');
    const variants = ['baseline', ...[...document.querySelectorAll('input[name="variant"]:checked')]
      .map((b) => b.value).filter((v) => v !== 'baseline')];
    const width = readPositiveInt('width', 'The width');
    const height = readPositiveInt('height', 'The height');
    const limits = state.catalog?.limits ?? {};
    if (isNum(limits.max_side) && (width > limits.max_side || height > limits.max_side)) {
      throw new Error(`A side can be at most ${fmtInt(limits.max_side)} pixels.`);
    }
    if (isNum(limits.max_pixels) && width * height > limits.max_pixels) {
      throw new Error(`${fmtInt(width)} × ${fmtInt(height)} is more than ${fmtInt(limits.max_pixels)} pixels.`);
    }
    const body = { scene, variants, size: [width, height], run };
    if ($('threads').value.trim() !== '') body.threads = readPositiveInt('threads', 'Threads');
    return body;
  }

  async function startRun() {
    let body;
    try {
      body = buildRequest();
    } catch (err) {
      showMessage(err.message);
      return;
    }
    const button = $('run-button');
    button.disabled = true;
    button.textContent = 'Starting…';
    try {
      const job = await api('POST', '/api/jobs', { body });
      if (job?.id == null) throw new Error('the server did not return a job');
      upsertJob(job);
      renderHistory();
      renderGateSelects();
      selectJob(job.id, { tab: 'view' });
      showMessage(`Job #${job.id} started (${jobScene(job)}).`, 'info');
      refreshJobs().catch(() => {});
    } catch (err) {
      reportError(err, 'Run');
    } finally {
      button.disabled = false;
      button.textContent = 'Run';
    }
  }

  // ---------------------------------------------------------------- History

  function jobOrder(a, b) {
    const x = Number(a.id);
    const y = Number(b.id);
    if (Number.isFinite(x) && Number.isFinite(y)) return y - x;
    return String(b.id).localeCompare(String(a.id));
  }

  function upsertJob(job) {
    const i = state.jobs.findIndex((j) => j.id === job.id);
    if (i >= 0) state.jobs[i] = job;
    else {
      state.jobs.push(job);
      state.jobs.sort(jobOrder);
    }
  }

  async function refreshJobs() {
    if (state.refreshing) {
      state.refreshAgain = true;
      return state.refreshing;
    }
    state.refreshing = (async () => {
      try {
        do {
          state.refreshAgain = false;
          const data = await api('GET', '/api/jobs');
          const jobs = Array.isArray(data?.jobs) ? data.jobs : [];
          // While a job is followed, its events are newer than any list that crossed them.
          const followed = state.follow ? jobById(state.follow.id) : null;
          state.jobs = jobs.map((j) => (followed && j.id === followed.id && !FINAL.has(j.status) ? followed : j));
          renderHistory();
          renderGateSelects();
          const selected = jobById(state.selectedId);
          if (selected && !(state.follow && state.follow.id === selected.id)) updateView(selected);
        } while (state.refreshAgain);
      } finally {
        state.refreshing = null;
      }
    })();
    return state.refreshing;
  }

  function renderHistory() {
    const list = $('history-list');
    const focusedId = document.activeElement?.classList?.contains('job-row') ? document.activeElement.dataset.id : null;
    if (!state.jobs.length) {
      list.replaceChildren(el('li', { class: 'empty' }, 'No jobs yet. Start one in Run.'));
      return;
    }
    list.replaceChildren(...state.jobs.map((job) => {
      const selected = job.id === state.selectedId;
      const fraction = job.progress?.fraction;
      const row = el('button', {
        type: 'button',
        class: `job-row${selected ? ' selected' : ''}`,
        'data-id': job.id,
        'aria-current': selected ? 'true' : null,
        title: `Job #${job.id}: ${jobScene(job)}, ${jobVariants(job)}`,
      },
      el('span', { class: 'job-row-top' },
        el('span', { class: 'job-id' }, `#${job.id}`),
        el('span', { class: 'job-scene' }, jobScene(job)),
        statusBadge(job.status)),
      el('span', { class: 'job-variants' }, jobVariants(job)),
      el('span', { class: 'job-row-bottom' },
        el('time', { class: 'job-created', datetime: job.created ?? null, title: job.created ?? null }, fmtTime(job.created)),
        ACTIVE.has(job.status) && isNum(fraction)
          ? el('span', { class: 'job-fraction' }, `${Math.round(fraction * 100)} %`)
          : null),
      ACTIVE.has(job.status)
        ? el('span', { class: 'job-mini-progress', 'aria-hidden': 'true' },
          el('span', { style: { width: `${Math.round((isNum(fraction) ? fraction : 0) * 100)}%` } }))
        : null);
      return el('li', {}, row);
    }));
    if (focusedId != null) list.querySelector(`.job-row[data-id="${CSS.escape(focusedId)}"]`)?.focus();
  }

  function markSelectedRow() {
    for (const row of document.querySelectorAll('#history-list .job-row')) {
      const on = row.dataset.id === state.selectedId;
      row.classList.toggle('selected', on);
      if (on) row.setAttribute('aria-current', 'true'); else row.removeAttribute('aria-current');
    }
  }

  // ---------------------------------------------------------------- selection and live progress

  async function selectJob(id, { tab } = {}) {
    if (id == null) return;
    id = String(id);
    if (state.selectedId !== id) {
      state.selectedId = id;
      state.viewKey = null;
      if (state.follow && state.follow.id !== id) stopFollowing();
    }
    markSelectedRow();
    if (tab) showTab(tab); else writeHash();
    let job = jobById(id);
    if (!job) {
      try {
        job = await api('GET', `/api/jobs/${encodeURIComponent(id)}`);
        upsertJob(job);
        renderHistory();
      } catch (err) {
        reportError(err, `Job #${id}`);
        return;
      }
    }
    updateView(job);
  }

  function stopFollowing() {
    if (state.follow) {
      state.follow.source.close();
      state.follow = null;
    }
  }

  function follow(id) {
    if (state.follow?.id === id) return;
    stopFollowing();
    if (typeof EventSource === 'undefined') return; // the poll keeps the page up to date
    const source = new EventSource(`/api/jobs/${encodeURIComponent(id)}/events`);
    state.follow = { id, source };
    source.addEventListener('job', (ev) => {
      if (state.follow?.source !== source) return;
      let job;
      try {
        job = JSON.parse(ev.data);
      } catch (_) {
        return;
      }
      if (!job || job.id == null) return;
      upsertJob(job);
      renderHistory();
      if (FINAL.has(job.status)) {
        stopFollowing();
        announceFinal(job);
        refreshJobs().catch((err) => reportError(err, 'Jobs'));
      }
      updateView(job);
    });
    source.addEventListener('error', () => {
      if (source.readyState === EventSource.CLOSED && state.follow?.source === source) {
        state.follow = null;
        refreshJob(id);
      }
      // Otherwise the browser reconnects by itself and the server sends the job again.
    });
  }

  function announceFinal(job) {
    const text = {
      done: `Job #${job.id} is done.`,
      failed: `Job #${job.id} failed${job.error ? `: ${job.error}` : '.'}`,
      cancelled: `Job #${job.id} was cancelled.`,
      interrupted: `Job #${job.id} was interrupted: the server stopped during it.`,
    }[job.status];
    if (text) showMessage(text, job.status === 'done' ? 'success' : job.status === 'failed' ? 'error' : 'info');
  }

  async function refreshJob(id) {
    try {
      const job = await api('GET', `/api/jobs/${encodeURIComponent(id)}`);
      upsertJob(job);
      renderHistory();
      updateView(job);
    } catch (err) {
      reportError(err, `Job #${id}`);
    }
  }

  async function cancelJob() {
    const id = state.selectedId;
    if (!id) return;
    const button = $('cancel-button');
    button.disabled = true;
    try {
      const job = await api('DELETE', `/api/jobs/${encodeURIComponent(id)}`);
      if (job?.id != null) {
        upsertJob(job);
        renderHistory();
        updateView(job);
      }
      showMessage(`Cancelling job #${id}…`, 'info');
    } catch (err) {
      if (err instanceof ApiError && err.status === 409) {
        showMessage(`Job #${id} has already finished.`, 'info');
        refreshJob(id);
      } else {
        reportError(err, 'Cancel');
        button.disabled = false;
      }
    }
  }

  function poll() {
    if (document.hidden) return;
    const stale = state.jobs.some((j) => ACTIVE.has(j.status) && !(state.follow && state.follow.id === j.id));
    if (stale) refreshJobs().catch(() => {});
    else if (state.follow) {
      // Keep the running time in the meta list moving.
      const job = jobById(state.follow.id);
      if (job) renderJobHead(job);
    }
  }

  // ---------------------------------------------------------------- View

  function updateView(job) {
    if (!job || job.id !== state.selectedId) return;
    $('view-empty').hidden = true;
    $('view-job').hidden = false;
    renderJobHead(job);
    renderOpen(job);
    if (!FINAL.has(job.status)) {
      follow(job.id);
      const key = `${job.id}:${job.status}`;
      if (state.viewKey !== key) {
        state.viewKey = key;
        $('results').replaceChildren(el('p', { class: 'muted placeholder' },
          job.status === 'queued'
            ? 'The job waits for the one before it. Results appear here when it is done.'
            : 'Results appear here when the job is done.'));
      }
      return;
    }
    if (state.follow?.id === job.id) stopFollowing();
    const key = `${job.id}:${job.status}`;
    if (state.viewKey === key) return;
    state.viewKey = key;
    if (job.status === 'done') loadResults(job);
    else renderUnfinished(job);
  }

  function renderJobHead(job) {
    $('view-title').textContent = `Job #${job.id}`;
    $('view-badge').replaceChildren(statusBadge(job.status));

    const req = job.request ?? {};
    const meta = [
      ['Scene', jobScene(job)],
      ['Variants', jobVariants(job)],
      ['Parts', Array.isArray(req.run) && req.run.length ? req.run.join(', ') : 'render'],
      ['Size', Array.isArray(req.size) ? `${req.size[0]} × ${req.size[1]}` : '—'],
      ['Threads', req.threads == null ? 'all cores' : String(req.threads)],
      ['Created', fmtTime(job.created)],
    ];
    if (job.started) meta.push(['Started', fmtTime(job.started)]);
    if (job.finished) meta.push(['Finished', fmtTime(job.finished)]);
    const took = job.started ? fmtDuration(job.started, job.finished) : null;
    if (took) meta.push([job.finished ? 'Took' : 'Running for', took]);
    $('view-meta').replaceChildren(...meta.map(([k, v]) => el('div', { class: 'meta-item' }, el('dt', {}, k), el('dd', {}, v))));

    const progress = $('job-progress');
    const fraction = job.progress?.fraction;
    if (job.status === 'done') progress.value = 1;
    else if (isNum(fraction)) progress.value = Math.min(1, Math.max(0, fraction));
    else if (job.status === 'queued' || job.status === 'running') progress.removeAttribute('value');
    progress.classList.toggle('final', FINAL.has(job.status));
    progress.dataset.status = cssPart(job.status);

    const p = job.progress ?? {};
    let status = String(job.status ?? 'unknown');
    if (p.message && ACTIVE.has(job.status)) status += ` — ${p.message}`;
    else if (p.message && job.status !== 'done') status += ` — stopped at: ${p.message}`;
    else if (p.stage && ACTIVE.has(job.status)) status += ` — ${p.stage}${isNum(p.done) && isNum(p.total) ? ` ${p.done}/${p.total}` : ''}`;
    if (ACTIVE.has(job.status) && isNum(fraction)) status += ` (${Math.round(fraction * 100)} %)`;
    $('job-status').textContent = status;

    const error = $('job-error');
    error.textContent = job.error ? `Error: ${job.error}` : '';
    error.hidden = !job.error;

    const cancel = $('cancel-button');
    cancel.hidden = !ACTIVE.has(job.status);
    cancel.disabled = !ACTIVE.has(job.status);
  }

  function renderUnfinished(job) {
    const explain = {
      failed: 'The job failed; it wrote no results.json.',
      cancelled: 'The job was cancelled; it wrote no results.json.',
      interrupted: 'The server stopped while the job ran; it wrote no results.json.',
    }[job.status] ?? `The job is ${job.status}.`;
    const files = Array.isArray(job.files) ? job.files : [];
    const partial = files.filter((f) => f.startsWith('partial/'));
    const shown = partial.length ? partial : files;
    $('results').replaceChildren(
      el('section', { class: 'result-block' },
        el('h3', {}, 'No results'),
        el('p', {}, explain),
        el('h4', {}, partial.length ? 'Partial outputs' : 'Files'),
        shown.length ? fileList(job.id, shown) : el('p', { class: 'muted' }, 'The job kept no partial outputs.')),
    );
  }

  function fileList(jobId, files) {
    return el('ul', { class: 'file-list' }, files.map((f) => el('li', {},
      el('a', { href: fileUrl(jobId, f), target: '_blank', rel: 'noopener' }, f))));
  }

  async function loadResults(job) {
    const box = $('results');
    let results = state.results.get(job.id);
    if (!results) {
      box.replaceChildren(el('p', { class: 'muted placeholder' }, 'Loading results…'));
      try {
        results = await api('GET', fileUrl(job.id, 'results.json'));
      } catch (err) {
        if (state.selectedId === job.id) {
          state.viewKey = null;
          box.replaceChildren(el('p', { class: 'error-box' }, `Cannot load results.json: ${err.message}`));
        }
        reportError(err, `Results of job #${job.id}`);
        return;
      }
      if (!results || typeof results !== 'object') {
        box.replaceChildren(el('p', { class: 'error-box' }, 'results.json is empty or not an object.'));
        return;
      }
      state.results.set(job.id, results);
    }
    if (state.selectedId !== job.id) return;
    try {
      renderResults(job, results);
    } catch (err) {
      box.replaceChildren(el('p', { class: 'error-box' }, `Cannot show the results: ${err.message}`));
      console.error(err);
    }
  }

  function renderResults(job, results) {
    const box = $('results');
    const scenes = Array.isArray(results.scenes) ? results.scenes : [];
    const blocks = [];

    const failures = Array.isArray(results.failures) ? results.failures : [];
    if (failures.length) blocks.push(renderFailures(failures));

    const sceneBox = el('div', { class: 'scene-results' });
    if (scenes.length > 1) {
      const picker = el('select', { id: 'result-scene' },
        scenes.map((s, i) => el('option', { value: String(i) },
          `${s.name} (${s.width}×${s.height}, ${fmtInt(s.primitives)} primitives)`)));
      picker.addEventListener('change', () => {
        sceneBox.replaceChildren(...renderScene(job, scenes[Number(picker.value)] ?? scenes[0]));
      });
      blocks.push(el('div', { class: 'scene-picker' },
        el('label', { class: 'field', for: 'result-scene' }, `Scene (${scenes.length} in this run)`), picker));
    }
    blocks.push(sceneBox);
    if (scenes.length) sceneBox.replaceChildren(...renderScene(job, scenes[0]));
    else sceneBox.replaceChildren(el('p', { class: 'muted' }, 'The run has no scenes.'));

    if (results.profile) blocks.push(renderProfile(job, results.profile));

    box.replaceChildren(...blocks);
  }

  function failurePart(part) {
    if (part && typeof part === 'object' && part.variant) return `variant ${part.variant}`;
    return String(part ?? 'unknown');
  }

  function renderFailures(failures) {
    return el('section', { class: 'result-block failures' },
      el('h3', {}, `Failures (${failures.length})`),
      el('p', { class: 'hint' }, 'These parts of the run failed; the rest of the results stand.'),
      el('ul', {}, failures.map((f) => el('li', {},
        el('strong', {}, failurePart(f.part)),
        f.scene ? ` on ${f.scene}` : '',
        ': ', f.message ?? ''))));
  }

  function block(title, detail, ...children) {
    return el('section', { class: 'result-block' },
      el('h3', {}, title, detail ? el('span', { class: 'detail' }, detail) : null),
      ...children);
  }

  function renderScene(job, scene) {
    const variants = Array.isArray(scene.variants) ? scene.variants : [];
    const out = [];
    const counts = scene.primitive_counts && typeof scene.primitive_counts === 'object'
      ? Object.entries(scene.primitive_counts).filter(([, n]) => n).map(([k, n]) => `${fmtInt(n)} ${k}`).join(', ')
      : '';
    out.push(el('div', { class: 'scene-summary' },
      el('h3', {}, scene.name ?? 'scene'),
      el('span', { class: 'detail' },
        `${scene.width} × ${scene.height} pixels · ${fmtInt(scene.primitives)} primitives${counts ? ` (${counts})` : ''}${scene.family ? ` · family ${scene.family}` : ''}`)));

    if (variants.length) {
      out.push(renderImages(job, scene, variants));
      const heat = renderHeatMaps(job, scene, variants);
      if (heat) out.push(heat);
      const compare = renderCompare(job, scene, variants);
      if (compare) out.push(compare);
      out.push(renderCounts(variants));
    } else {
      out.push(el('p', { class: 'muted' }, 'No variant ran on this scene.'));
    }
    if (Array.isArray(scene.pixel_maps) && scene.pixel_maps.length) out.push(renderPixelMaps(job, scene.pixel_maps));
    if (scene.hardware) out.push(renderHardware(job, scene.hardware, scene));
    return out;
  }

  function pixelImage(src, alt, scene, cls) {
    return el('img', {
      src,
      alt,
      class: cls ?? null,
      width: isNum(scene?.width) ? scene.width : null,
      height: isNum(scene?.height) ? scene.height : null,
    });
  }

  function renderImages(job, scene, variants) {
    const grid = el('div', { class: 'image-grid' });
    for (const v of variants) {
      const isBaseline = v.variant === 'baseline';
      const time = v.time ?? {};
      const figure = el('figure', { class: `variant-image${isBaseline ? ' reference' : ''}` },
        v.image
          ? el('a', { href: fileUrl(job.id, v.image), target: '_blank', rel: 'noopener', title: 'Open the image' },
            pixelImage(fileUrl(job.id, v.image), `${v.variant} render of ${scene.name}`, scene))
          : el('div', { class: 'missing' }, 'no image'),
        el('figcaption', {},
          el('span', { class: 'cap-title' }, v.variant),
          el('span', { class: 'cap-line', title: isNum(time.low) ? `interval ${fmtMs(time.low)} – ${fmtMs(time.high)}` : null },
            `median ${fmtMs(time.median)}`),
          el('span', { class: 'cap-line' },
            isBaseline
              ? 'reference'
              : isNum(v.speedup)
                ? el('span', {
                  class: `speedup ${v.speedup >= 1 ? 'faster' : 'slower'}`,
                  title: Array.isArray(v.speedup_interval) ? `95 % interval ${fmtSpeedup(v.speedup_interval[0])} – ${fmtSpeedup(v.speedup_interval[1])}` : null,
                }, `${fmtSpeedup(v.speedup)} vs baseline`)
                : 'speed-up unknown',
            v.verdict ? el('span', { class: 'muted' }, ` (${String(v.verdict).replace(/_/g, ' ')})`) : null),
          v.quality
            ? el('span', { class: 'cap-line' }, bandChip(v.quality.band), ` RMS ${fmtFixed(v.quality.rms, 2)}`)
            : el('span', { class: 'cap-line muted' }, isBaseline ? 'the reference image' : 'no quality figures')));
      grid.append(figure);
    }
    return block('Images', 'side by side; speed-up and RMS against baseline', grid);
  }

  function renderHeatMaps(job, scene, variants) {
    const withMaps = variants.filter((v) => v.heat_map);
    if (!withMaps.length) return null;
    const grid = el('div', { class: 'image-grid' }, withMaps.map((v) => el('figure', { class: 'heat-figure' },
      el('a', { href: fileUrl(job.id, v.heat_map), target: '_blank', rel: 'noopener', title: 'Open the heat map' },
        pixelImage(fileUrl(job.id, v.heat_map), `difference of ${v.variant} from baseline`, scene, 'heat-map')),
      el('figcaption', {},
        el('span', { class: 'cap-title' }, `${v.variant} − baseline`),
        v.quality
          ? [
            el('span', { class: 'cap-line' }, bandChip(v.quality.band), ` RMS ${fmtFixed(v.quality.rms, 2)}`),
            el('span', { class: 'cap-line muted' },
              `max |Δ| ${fmtInt(v.quality.max_abs_diff)}`,
              isNum(v.quality.ssim) ? ` · SSIM ${fmtFixed(v.quality.ssim, 4)}` : '',
              isNum(v.quality.psnr) ? ` · PSNR ${fmtFixed(v.quality.psnr, 1)} dB` : (v.quality.rms === 0 ? ' · identical' : '')),
          ]
          : null))));
    return block('Difference heat maps', 'per-pixel difference from baseline', grid);
  }

  function renderCompare(job, scene, variants) {
    const withImages = variants.filter((v) => v.image);
    if (withImages.length < 2) return null;
    const options = () => withImages.map((v) => el('option', { value: v.variant }, v.variant));
    const selectA = el('select', { id: 'compare-a' }, options());
    const selectB = el('select', { id: 'compare-b' }, options());
    const a0 = withImages.find((v) => v.variant === 'baseline') ?? withImages[0];
    const b0 = withImages.find((v) => v !== a0) ?? withImages[1];
    selectA.value = a0.variant;
    selectB.value = b0.variant;

    const w = isNum(scene.width) && scene.width > 0 ? scene.width : 160;
    const h = isNum(scene.height) && scene.height > 0 ? scene.height : 120;
    const scale = w < COMPARE_WIDTH ? Math.max(1, Math.floor(COMPARE_WIDTH / w)) : 1;

    const imgA = el('img', { class: 'compare-img compare-img-a', alt: '', draggable: 'false' });
    const imgB = el('img', { class: 'compare-img compare-img-b', alt: '', draggable: 'false' });
    const divider = el('div', { class: 'compare-divider', 'aria-hidden': 'true' });
    const labelB = el('span', { class: 'compare-label compare-label-b' });
    const labelA = el('span', { class: 'compare-label compare-label-a' });
    const stage = el('div', {
      class: 'compare-stage',
      style: { width: `${w * scale}px`, aspectRatio: `${w} / ${h}` },
    }, imgA, imgB, divider, labelB, labelA);

    const slider = el('input', {
      type: 'range', id: 'compare-slider', min: '0', max: '100', step: '1', value: '50',
      'aria-label': 'How much of image B covers image A (from the left)',
    });
    const toggle = el('button', { type: 'button', id: 'compare-toggle', class: 'small' }, 'Toggle A / B');
    const readout = el('span', { class: 'hint compare-readout' });

    const find = (name) => withImages.find((v) => v.variant === name) ?? withImages[0];
    function setImages() {
      const a = find(selectA.value);
      const b = find(selectB.value);
      imgA.src = fileUrl(job.id, a.image);
      imgA.alt = `A: ${a.variant}`;
      imgB.src = fileUrl(job.id, b.image);
      imgB.alt = `B: ${b.variant}`;
      labelA.textContent = `A: ${a.variant}`;
      labelB.textContent = `B: ${b.variant}`;
    }
    function setReveal() {
      const value = Math.min(100, Math.max(0, Number(slider.value)));
      imgB.style.clipPath = `inset(0 ${100 - value}% 0 0)`;
      divider.style.left = `${value}%`;
      divider.hidden = value === 0 || value === 100;
      labelB.hidden = value === 0;
      labelA.hidden = value === 100;
      readout.textContent = value === 100 ? 'showing B' : value === 0 ? 'showing A' : `B on the left ${value} %, A on the right`;
    }
    selectA.addEventListener('change', setImages);
    selectB.addEventListener('change', setImages);
    slider.addEventListener('input', setReveal);
    toggle.addEventListener('click', () => {
      slider.value = Number(slider.value) >= 100 ? '0' : '100';
      setReveal();
    });
    // Dragging on the picture moves the split too.
    const fromPointer = (ev) => {
      const rect = stage.getBoundingClientRect();
      if (rect.width <= 0) return;
      slider.value = String(Math.round(Math.min(1, Math.max(0, (ev.clientX - rect.left) / rect.width)) * 100));
      setReveal();
    };
    stage.addEventListener('pointerdown', (ev) => {
      stage.setPointerCapture(ev.pointerId);
      fromPointer(ev);
    });
    stage.addEventListener('pointermove', (ev) => {
      if (ev.buttons & 1) fromPointer(ev);
    });
    setImages();
    setReveal();

    return block('Compare', `${scale > 1 ? `scaled ${scale}×, ` : ''}B revealed over A`,
      el('div', { class: 'compare-controls' },
        el('label', { class: 'field' }, 'A', selectA),
        el('label', { class: 'field' }, 'B', selectB),
        el('label', { class: 'field grow' }, 'Reveal B', slider),
        toggle,
        readout),
      el('div', { class: 'compare-wrap' }, stage));
  }

  function renderCounts(variants) {
    const keys = [...new Set(variants.flatMap((v) => Object.keys(v.counts ?? {})))].sort();
    if (!keys.length) return block('Counts', null, el('p', { class: 'muted' }, 'No counts.'));
    const baseline = variants.find((v) => v.variant === 'baseline');
    const table = el('table', { id: 'counts-table', class: 'data' },
      el('thead', {}, el('tr', {},
        el('th', { scope: 'col' }, 'counter'),
        variants.map((v) => el('th', { scope: 'col', class: 'num' }, v.variant)))),
      el('tbody', {}, keys.map((key) => el('tr', {},
        el('th', { scope: 'row' }, el('code', {}, key)),
        variants.map((v) => {
          const n = v.counts?.[key];
          const ref = baseline?.counts?.[key];
          const changed = baseline && v !== baseline && isNum(n) && isNum(ref) && n !== ref;
          return el('td', {
            class: `num${changed ? (n < ref ? ' less' : ' more') : ''}`,
            title: changed && ref ? `${fmtFixed((n / ref) * 100, 1)} % of baseline` : null,
          }, isNum(n) ? fmtInt(n) : '—');
        })))));
    return block('Counts', 'exact, per render; green fewer / red more than baseline',
      el('div', { class: 'table-wrap' }, table));
  }

  function renderPixelMaps(job, sets) {
    const children = [];
    for (const set of sets) {
      const maps = Array.isArray(set.maps) ? set.maps : [];
      children.push(el('h4', {}, set.variant ?? 'variant',
        el('span', { class: 'detail' }, ` ${set.columns} × ${set.rows} samples`)));
      children.push(el('div', { class: 'map-grid' }, maps.map((m) => {
        const src = fileUrl(job.id, joinPath(set.directory, m.png));
        return el('figure', { class: 'pixel-map', title: m.description ?? null },
          el('a', { href: src, target: '_blank', rel: 'noopener' },
            el('img', { src, alt: `${m.key} per sample` })),
          el('figcaption', {},
            el('span', { class: 'cap-title' }, el('code', {}, m.key)),
            el('span', { class: 'cap-line muted' }, m.unit ?? ''),
            el('span', { class: 'cap-line' },
              `min ${fmtInt(m.min)} · mean ${fmtMean(m.mean)} · max ${fmtInt(m.max)}`)));
      })));
    }
    return block('Per-pixel maps', 'false colour, one value per sample', ...children);
  }

  function renderHardware(job, hw, scene) {
    const rows = [
      ['Cycles', fmtInt(hw.cycles)],
      ['Time on the FPGA model', fmtMs(hw.seconds)],
      ['Fits the device', el('span', { class: `badge ${hw.fits ? 'status-done' : 'status-failed'}` }, hw.fits ? 'yes' : 'no')],
      ['Speed-up vs software', fmtSpeedup(hw.speedup)],
      ['Software time (diffuse only)', fmtMs(hw.software_seconds?.median)],
      ['Emulator vs software', [bandChip(hw.emulator_band), ` RMS ${fmtFixed(hw.emulator_rms, 2)}`]],
    ];
    if (isNum(hw.primitives)) rows.splice(1, 0, ['Primitives', fmtInt(hw.primitives)]);
    const table = el('table', { class: 'kv' }, el('tbody', {}, rows.map(([k, v]) => el('tr', {},
      el('th', { scope: 'row' }, k), el('td', { class: 'num' }, v)))));
    const figures = [];
    if (hw.emulator_image) {
      figures.push(el('figure', { class: 'hw-image' },
        pixelImage(fileUrl(job.id, hw.emulator_image), 'emulator image', scene),
        el('figcaption', {}, el('span', { class: 'cap-title' }, 'hardware emulator'))));
    }
    if (hw.software_image) {
      figures.push(el('figure', { class: 'hw-image' },
        pixelImage(fileUrl(job.id, hw.software_image), 'software diffuse-only image', scene),
        el('figcaption', {}, el('span', { class: 'cap-title' }, 'software, diffuse only'))));
    }
    return block('Hardware', 'the FPGA model and its emulator',
      el('div', { class: 'hardware' }, table,
        figures.length ? el('div', { class: 'image-grid pair' }, figures) : el('p', { class: 'muted' }, 'No images.')));
  }

  function flame(job, path, caption) {
    const url = fileUrl(job.id, path);
    return el('figure', { class: 'flame' },
      el('object', { type: 'image/svg+xml', data: url, class: 'flame-svg', 'aria-label': caption },
        el('a', { href: url, target: '_blank', rel: 'noopener' }, `Open ${caption}`)),
      el('figcaption', {}, caption, ' · ',
        el('a', { href: url, target: '_blank', rel: 'noopener' }, 'open alone')));
  }

  function renderProfile(job, profile) {
    const children = [];
    const base = profile.baseline;
    const best = profile.best;
    if (base?.flame_svg) {
      children.push(flame(job, base.flame_svg,
        `Flamegraph of ${base.variant ?? 'baseline'} (${fmtInt(base.samples)} samples)`));
    }
    if (best?.flame_svg) {
      children.push(flame(job, best.flame_svg,
        `Flamegraph of ${best.variant ?? 'the best variant'}, the best variant (${fmtInt(best.samples)} samples)`));
    }
    if (profile.diff_flame_svg) {
      children.push(flame(job, profile.diff_flame_svg,
        `Differential flamegraph ${base?.variant ?? 'baseline'} → ${best?.variant ?? 'best'}: what grew`));
    }
    if (profile.diff_shrunk_flame_svg) {
      children.push(flame(job, profile.diff_shrunk_flame_svg,
        `Differential flamegraph ${base?.variant ?? 'baseline'} → ${best?.variant ?? 'best'}: what shrank`));
    }
    const flat = Array.isArray(base?.flat) ? [...base.flat] : [];
    flat.sort((x, y) => (y.percent ?? 0) - (x.percent ?? 0));
    if (flat.length) {
      children.push(el('h4', {}, `Flat profile of ${base.variant ?? 'baseline'}`,
        el('span', { class: 'detail' }, ` top ${Math.min(10, flat.length)} of ${flat.length} by self time`)));
      children.push(el('div', { class: 'table-wrap' }, el('table', { id: 'flat-table', class: 'data' },
        el('thead', {}, el('tr', {},
          el('th', { scope: 'col' }, 'function'),
          el('th', { scope: 'col', class: 'num' }, 'self %'),
          el('th', { scope: 'col', class: 'num' }, 'self seconds'),
          el('th', { scope: 'col', class: 'num' }, 'calls'))),
        el('tbody', {}, flat.slice(0, 10).map((row) => el('tr', { class: row.noise ? 'noise' : null },
          el('td', { class: 'fn' }, el('code', {}, row.name)),
          el('td', { class: 'num' }, `${fmtFixed(row.percent, 1)} %`),
          el('td', { class: 'num' }, fmtSeconds(row.self_seconds)),
          el('td', { class: 'num' }, isNum(row.calls) ? fmtInt(row.calls) : '—')))))));
    }
    if (!children.length) children.push(el('p', { class: 'muted' }, 'The profile has no flamegraph.'));
    return block('Profile', `${profile.scene ?? ''}${isNum(profile.width) ? `, ${profile.width} × ${profile.height}` : ''}`, ...children);
  }

  // ---------------------------------------------------------------- Open

  function setLink(a, href) {
    if (href) {
      a.href = href;
      a.removeAttribute('aria-disabled');
    } else {
      a.removeAttribute('href');
      a.setAttribute('aria-disabled', 'true');
    }
  }

  function renderOpen(job) {
    const files = new Set(Array.isArray(job?.files) ? job.files : []);
    const done = job?.status === 'done';
    const has = (f) => job && (files.has(f) || (done && files.size === 0));
    $('open-job').replaceChildren(...(job
      ? [`#${job.id} · ${jobScene(job)} · `, statusBadge(job.status)]
      : ['none selected']));
    setLink($('open-report'), has('report.html') ? fileUrl(job.id, 'report.html') : null);
    const pdf = $('open-pdf');
    const json = $('open-results');
    setLink(pdf, has('report.pdf') ? fileUrl(job.id, 'report.pdf') : null);
    setLink(json, has('results.json') ? fileUrl(job.id, 'results.json') : null);
    if (job) {
      pdf.setAttribute('download', `rtprof-job-${job.id}-report.pdf`);
      json.setAttribute('download', `rtprof-job-${job.id}-results.json`);
    }
    let note = '';
    if (!job) note = 'Select a job in History.';
    else if (ACTIVE.has(job.status)) note = 'The report and results are written when the job is done.';
    else if (!done) note = `The job is ${job.status}: it has no report.`;
    $('open-note').textContent = note;
    const list = $('open-files');
    if (!job) list.replaceChildren(el('li', { class: 'muted' }, 'No job selected.'));
    else if (!files.size) list.replaceChildren(el('li', { class: 'muted' }, ACTIVE.has(job.status) ? 'Not yet.' : 'No files.'));
    else list.replaceChildren(...[...files].sort().map((f) => el('li', {},
      el('a', { href: fileUrl(job.id, f), target: '_blank', rel: 'noopener' }, f))));
  }

  // ---------------------------------------------------------------- Gate

  function renderGateSelects() {
    const done = state.jobs.filter((j) => j.status === 'done');
    const oldSel = $('gate-old');
    const newSel = $('gate-new');
    const prevOld = oldSel.value;
    const prevNew = newSel.value;
    const options = () => done.map((j) => el('option', { value: j.id },
      `#${j.id} · ${jobScene(j)} · ${jobVariants(j)} · ${fmtTime(j.created)}`));
    if (!done.length) {
      oldSel.replaceChildren(el('option', { value: '' }, 'no finished jobs'));
      newSel.replaceChildren(el('option', { value: '' }, 'no finished jobs'));
      $('gate-button').disabled = true;
      return;
    }
    oldSel.replaceChildren(...options());
    newSel.replaceChildren(...options());
    const ids = new Set(done.map((j) => j.id));
    newSel.value = ids.has(prevNew) ? prevNew : done[0].id;
    oldSel.value = ids.has(prevOld) ? prevOld : (done[1] ?? done[0]).id;
    $('gate-button').disabled = false;
  }

  async function runGate() {
    const oldId = $('gate-old').value;
    const newId = $('gate-new').value;
    const output = $('gate-output');
    const badge = $('gate-badge');
    const error = $('gate-error');
    if (!oldId || !newId) {
      error.textContent = 'Choose two finished jobs.';
      error.hidden = false;
      return;
    }
    error.hidden = true;
    badge.hidden = true;
    output.hidden = false;
    output.textContent = 'Comparing…';
    const button = $('gate-button');
    button.disabled = true;
    try {
      const data = await api('GET', `/api/gate?old=${encodeURIComponent(oldId)}&new=${encodeURIComponent(newId)}`);
      const passed = Boolean(data?.passed);
      badge.textContent = passed ? 'passed' : 'failed';
      badge.className = `badge ${passed ? 'status-done' : 'status-failed'}`;
      badge.hidden = false;
      output.textContent = data?.text ?? '';
    } catch (err) {
      output.hidden = true;
      output.textContent = '';
      if (err instanceof ApiError && [400, 404, 422].includes(err.status)) {
        error.textContent = err.message;
        error.hidden = false;
      } else {
        reportError(err, 'Gate');
      }
    } finally {
      button.disabled = false;
    }
  }

  // ---------------------------------------------------------------- start

  function wire() {
    wireTabs();
    $('scene').addEventListener('change', (ev) => {
      if (ev.target.value) chooseScene(ev.target.value);
    });
    $('generator').addEventListener('change', onGeneratorChange);
    $('generator-param').addEventListener('input', updateGeneratorPreview);
    $('generator-param').addEventListener('keydown', (ev) => {
      if (ev.key === 'Enter') {
        ev.preventDefault();
        useGenerator();
      }
    });
    $('generator-use').addEventListener('click', useGenerator);
    $('upload-form').addEventListener('submit', upload);
    $('upload-file').addEventListener('change', () => {
      showUploadError('');
      updateUploadPlaceholder();
    });
    $('variants-all').addEventListener('click', () => setAllVariants(true));
    $('variants-none').addEventListener('click', () => setAllVariants(false));
    for (const button of document.querySelectorAll('[data-size]')) {
      button.addEventListener('click', () => {
        const [w, h] = button.dataset.size.split('x');
        $('width').value = w;
        $('height').value = h;
      });
    }
    $('run-button').addEventListener('click', startRun);
    $('cancel-button').addEventListener('click', cancelJob);
    $('history-list').addEventListener('click', (ev) => {
      const row = ev.target.closest('.job-row');
      if (row) selectJob(row.dataset.id, { tab: state.tab === 'open' ? 'open' : 'view' });
    });
    $('history-refresh').addEventListener('click', () => {
      refreshJobs().catch((err) => reportError(err, 'Jobs'));
    });
    $('gate-button').addEventListener('click', runGate);
    document.addEventListener('visibilitychange', () => {
      if (!document.hidden) refreshJobs().catch(() => {});
    });
    window.addEventListener('beforeunload', stopFollowing);
  }

  async function init() {
    wire();
    const hash = readHash();
    showTab(hash.tab || 'pick', { updateHash: false });
    renderOpen(null);
    await Promise.all([
      loadCatalog(true).catch((err) => reportError(err, 'Loading scenes')),
      refreshJobs().catch((err) => {
        $('history-list').replaceChildren(el('li', { class: 'empty' }, 'Cannot load the jobs.'));
        reportError(err, 'Loading jobs');
      }),
    ]);
    if (hash.job) selectJob(hash.job, {});
    setInterval(poll, POLL_MS);
  }

  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', init);
  else init();
})();
