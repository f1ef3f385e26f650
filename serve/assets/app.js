// rtprof serve: the page's script. Vanilla ES2020, no dependencies, no network
// reference outside this server. Every piece of data is inserted as text
// (textContent / createElement), never as HTML. It formats no number: every figure
// comes from the API already written by the reports' formatter (reports::format),
// so the page and the report cannot write one value two ways.
'use strict';

(() => {
  // ---------------------------------------------------------------- constants

  const FINAL = new Set(['done', 'failed', 'cancelled', 'interrupted']);
  const ACTIVE = new Set(['queued', 'running']);
  const TABS = ['pick', 'run', 'view', 'open', 'gate'];
  const GROUPS = [['builtin', 'built-in'], ['uploaded', 'uploaded']];
  const POLL_MS = 2000; // also how soon a lost server is noticed without a live job
  const FORM_KEY = 'rtprof-form';

  const token = document.querySelector('meta[name="rtprof-token"]')?.getAttribute('content') ?? '';

  const state = {
    catalog: null, // GET /api/scenes
    generated: [], // generated scene ids chosen in this session
    chosenScene: null,
    jobs: [], // newest first
    selectedId: null,
    follow: null, // { id, source } the EventSource of the followed job
    values: new Map(), // job id -> GET /api/jobs/ID/values (finished jobs do not change)
    besideId: null, // a second finished job shown beside the selected one
    lost: false, // the server does not answer
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

  /** The URL of a job's file; each path segment is encoded. */
  function fileUrl(jobId, path) {
    const segments = String(path).split('/').filter((s) => s !== '' && s !== '.' && s !== '..');
    return `/api/jobs/${encodeURIComponent(jobId)}/files/${segments.map(encodeURIComponent).join('/')}`;
  }

  function joinPath(dir, name) {
    if (!dir) return name;
    return `${String(dir).replace(/\/+$/, '')}/${name}`;
  }

  /** A band chip from the API's band values (name, key, thesis range as title). */
  function bandChip(band) {
    if (!band) return null;
    return el('span', { class: `band band-${cssPart(band.key)}`, title: band.title }, band.name);
  }

  function statusBadge(status) {
    return el('span', { class: `badge status-${cssPart(status)}` }, String(status ?? 'unknown'));
  }

  const jobScene = (job) => job?.text?.scene ?? job?.request?.scene ?? '';
  const jobVariants = (job) => job?.text?.variants ?? '';

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
    serverBack();
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

  /**
   * Shows a message in the status area, a fixed strip that moves nothing on the page;
   * a newer message replaces an older one. Errors stay until dismissed.
   */
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
    if (err instanceof ApiError && err.status === 0) {
      serverLost();
      return;
    }
    const text = err instanceof Error ? err.message : String(err);
    showMessage(context ? `${context}: ${text}` : text, 'error');
    if (!(err instanceof ApiError)) console.error(err);
  }

  /** The server stopped answering: say so, stop the clocks, keep trying. */
  function serverLost() {
    if (state.lost) return;
    state.lost = true;
    stopFollowing();
    const banner = $('lost-banner');
    banner.hidden = false;
    document.body.classList.add('server-lost');
  }

  /** It answers again: the banner goes, the jobs are read again. */
  function serverBack() {
    if (!state.lost) return;
    state.lost = false;
    $('lost-banner').hidden = true;
    document.body.classList.remove('server-lost');
    state.viewKey = null;
    refreshJobs().catch(() => {});
  }

  // ---------------------------------------------------------------- tabs

  function showTab(name, { updateHash = true, focus = false } = {}) {
    if (!TABS.includes(name)) name = 'pick';
    state.tab = name;
    for (const t of TABS) {
      const on = t === name;
      const button = $(`tab-${t}`);
      button.setAttribute('aria-selected', String(on));
      // Every tab is on the Tab path (Gate too), arrows move between them as well.
      button.tabIndex = 0;
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
      renderTracers();
      renderParts();
      applyLimits();
    }
  }

  const sceneLabel = (s) => s.label ?? s.id;

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
    updateEstimate();
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
    $('generator-range').textContent = g.range ?? '';
    $('generator-summary').textContent = g.summary ? `${g.summary}.`.replace(/\.\.$/, '.') : '';
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
      showMessage(`${g.label ?? g.prefix}: the ${g.parameter ?? 'parameter'} must be a whole number in the range ${g.range ?? ''}`);
      return;
    }
    const id = `${g.prefix}:${n}`;
    if (!state.generated.includes(id)) state.generated.push(id);
    state.chosenScene = id;
    renderSceneSelect();
    chooseScene(id);
    showMessage(`Scene ${id} chosen.`, 'info');
    saveForm();
    updateEstimate();
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
      showMessage(`Uploaded ${scene?.label ?? name}; it is now the chosen scene.`, 'info');
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

  /** The outside tracers the server loaded at start, each a checkbox by its name. */
  function renderTracers() {
    const tracers = state.catalog?.tracers ?? [];
    $('tracers-fieldset').hidden = !tracers.length;
    $('tracer-list').replaceChildren(...tracers.map((t) => el('label', { class: 'check' },
      el('input', { type: 'checkbox', name: 'tracer', value: t.name }),
      el('span', { class: 'check-body' },
        el('span', { class: 'check-name' }, t.variant),
        el('span', { class: 'check-summary' }, t.description || t.definition),
        el('span', { class: 'check-summary' }, `${t.command} · its time covers ${t.time_covers}`),
      ))));
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
    if (isNum(limits.max_threads)) $('threads').max = String(limits.max_threads);
    $('size-hint').textContent = limits.size_text ?? '';
    $('upload-limit').textContent = limits.upload_text ?? '';
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
    const tracers = [...document.querySelectorAll('input[name="tracer"]:checked')].map((b) => b.value);
    const body = { scene, variants, size: [width, height], run };
    if (tracers.length) body.tracers = tracers;
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
    saveForm();
    const button = $('run-button');
    button.disabled = true;
    button.textContent = 'Starting…';
    try {
      await submit(body);
    } finally {
      button.disabled = false;
      button.textContent = 'Run';
    }
  }

  /** Queues a job and shows it in View, the View tab focused (not the page's body). */
  async function submit(body) {
    try {
      const job = await api('POST', '/api/jobs', { body });
      if (job?.id == null) throw new Error('the server did not return a job');
      upsertJob(job);
      renderHistory();
      renderGateSelects();
      selectJob(job.id, { tab: 'view', focus: true });
      showMessage(`Job #${job.id} started (${jobScene(job)}).`, 'info');
      refreshJobs().catch(() => {});
    } catch (err) {
      reportError(err, 'Run');
    }
  }

  // ---------------------------------------------------------------- the form, kept

  /** The Run form in localStorage, so that a reload keeps it. */
  function saveForm() {
    const form = {
      scene: state.chosenScene,
      generated: state.generated,
      variants: [...document.querySelectorAll('input[name="variant"]:checked')].map((b) => b.value),
      parts: [...document.querySelectorAll('input[name="part"]:checked')].map((b) => b.value),
      tracers: [...document.querySelectorAll('input[name="tracer"]:checked')].map((b) => b.value),
      width: $('width').value,
      height: $('height').value,
      threads: $('threads').value,
    };
    try {
      localStorage.setItem(FORM_KEY, JSON.stringify(form));
    } catch (_) {
      // Storage refused (private mode): the form is simply not kept.
    }
  }

  function restoreForm() {
    let form;
    try {
      form = JSON.parse(localStorage.getItem(FORM_KEY) ?? 'null');
    } catch (_) {
      form = null;
    }
    if (!form || typeof form !== 'object') return;
    if (Array.isArray(form.generated)) state.generated = form.generated.filter((g) => typeof g === 'string');
    for (const id of ['width', 'height', 'threads']) {
      if (typeof form[id] === 'string') $(id).value = form[id];
    }
    if (Array.isArray(form.variants)) {
      for (const box of document.querySelectorAll('input[name="variant"]')) {
        if (box.value !== 'baseline') box.checked = form.variants.includes(box.value);
      }
    }
    if (Array.isArray(form.tracers)) {
      for (const box of document.querySelectorAll('input[name="tracer"]')) box.checked = form.tracers.includes(box.value);
    }
    if (Array.isArray(form.parts)) {
      for (const box of document.querySelectorAll('input[name="part"]')) box.checked = form.parts.includes(box.value);
      onPartsChange();
    }
    if (typeof form.scene === 'string' && form.scene) {
      renderSceneSelect();
      chooseScene(form.scene);
    }
  }

  // ---------------------------------------------------------------- the estimate

  let estimateTimer = null;
  let estimateAsked = 0;

  /** Asks the server what the chosen scene and size would cost (after a pause in typing). */
  function updateEstimate() {
    clearTimeout(estimateTimer);
    estimateTimer = setTimeout(async () => {
      const box = $('estimate');
      const scene = state.chosenScene;
      const width = $('width').value.trim();
      const height = $('height').value.trim();
      const threads = $('threads').value.trim();
      if (!scene || !width || !height) {
        box.textContent = '';
        return;
      }
      const asked = ++estimateAsked;
      const query = new URLSearchParams({ scene, width, height });
      if (threads) query.set('threads', threads);
      box.textContent = 'Estimating…';
      try {
        const estimate = await api('GET', `/api/estimate?${query}`);
        if (asked === estimateAsked) box.textContent = `Before you run: ${estimate?.text ?? ''}.`;
      } catch (err) {
        if (asked === estimateAsked) box.textContent = err.status === 0 ? '' : `No estimate: ${err.message}`;
      }
    }, 300);
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
          const signature = JSON.stringify(state.jobs.map((j) => [j.id, j.status, j.text?.elapsed]));
          if (signature !== state.historySignature) {
            state.historySignature = signature;
            renderHistory();
          }
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
        el('time', { class: 'job-created', datetime: job.created ?? null }, job.text?.created ?? ''),
        job.text?.elapsed ? el('span', { class: 'job-fraction' }, job.text.elapsed) : null));
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

  async function selectJob(id, { tab, focus = false } = {}) {
    if (id == null) return;
    id = String(id);
    if (state.selectedId !== id) {
      state.selectedId = id;
      state.viewKey = null;
      if (state.follow && state.follow.id !== id) stopFollowing();
    }
    markSelectedRow();
    if (tab) showTab(tab, { focus }); else writeHash();
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
      if (state.follow?.source !== source) return;
      // The stream of a running job never ends by itself: the server is gone (or
      // restarting). Say so at once, stop the clock, and let the poll find it again.
      source.close();
      state.follow = null;
      serverLost();
      refreshJob(id);
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
      const job = await api('POST', `/api/jobs/${encodeURIComponent(id)}/cancel`);
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

  /** Re-runs the selected job: the same request, a new job. */
  function rerunJob() {
    const job = jobById(state.selectedId);
    if (job?.request) submit(job.request);
  }

  /** Deletes the selected finished job and its files (after asking). */
  async function deleteJob() {
    const id = state.selectedId;
    const job = jobById(id);
    if (!job || !FINAL.has(job.status)) return;
    if (!window.confirm(`Delete job #${id} and all its files?`)) return;
    try {
      await api('DELETE', `/api/jobs/${encodeURIComponent(id)}`);
    } catch (err) {
      reportError(err, 'Delete');
      return;
    }
    state.jobs = state.jobs.filter((j) => j.id !== id);
    state.values.delete(id);
    if (state.besideId === id) state.besideId = null;
    state.selectedId = null;
    state.viewKey = null;
    $('view-job').hidden = true;
    $('view-empty').hidden = false;
    renderHistory();
    renderGateSelects();
    renderOpen(null);
    writeHash();
    showMessage(`Job #${id} deleted.`, 'info');
    $('tab-view').focus();
  }

  /** Every POLL_MS: the jobs not followed live, and whether the server still answers. */
  function poll() {
    if (document.hidden) return;
    refreshJobs().catch((err) => {
      if (err instanceof ApiError && err.status === 0) serverLost();
    });
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
    const key = `${job.id}:${job.status}:${state.besideId ?? ''}`;
    if (state.viewKey === key) return;
    state.viewKey = key;
    if (job.status === 'done') loadResults(job);
    else renderUnfinished(job);
  }

  function renderJobHead(job) {
    $('view-title').textContent = `Job #${job.id}`;
    $('view-badge').replaceChildren(statusBadge(job.status));

    const req = job.request ?? {};
    const text = job.text ?? {};
    const meta = [
      ['Scene', text.scene],
      ['Variants', text.variants],
      ['Parts', Array.isArray(req.run) && req.run.length ? req.run.join(', ') : 'render'],
      ['Size', text.size],
      ['Threads', text.threads],
      ['Created', text.created],
    ];
    if (text.started) meta.push(['Started', text.started]);
    if (text.finished) meta.push(['Finished', text.finished]);
    if (text.elapsed) meta.push([job.finished ? 'Took' : 'Running for', text.elapsed]);
    $('view-meta').replaceChildren(...meta.map(([k, v]) => el('div', { class: 'meta-item' }, el('dt', {}, k), el('dd', {}, v ?? ''))));

    // The bar shows the current stage's own share when the runner counts it, and
    // moves without a share (indeterminate) when it does not.
    const progress = $('job-progress');
    const active = ACTIVE.has(job.status);
    progress.hidden = !active;
    if (isNum(text.stage_fraction)) progress.value = text.stage_fraction;
    else progress.removeAttribute('value');
    $('job-status').textContent = active ? (text.progress || String(job.status)) : '';

    // A failure is an error; a cancel or an interruption is what the user or the
    // machine did, said plainly.
    const error = $('job-error');
    error.textContent = job.error ? (job.status === 'failed' ? `Error: ${job.error}` : job.error) : '';
    error.className = job.status === 'failed' ? 'error-box' : 'note-box';
    error.hidden = !job.error;

    const cancel = $('cancel-button');
    cancel.hidden = !active;
    cancel.disabled = !active;
    $('rerun-button').hidden = active;
    $('delete-button').hidden = active;
    renderBesideSelect(job);
  }

  /** The select of a second finished job to show beside this one. */
  function renderBesideSelect(job) {
    const select = $('beside-select');
    const others = state.jobs.filter((j) => j.status === 'done' && j.id !== job.id);
    const wrap = $('beside');
    wrap.hidden = job.status !== 'done' || !others.length;
    const current = state.besideId;
    select.replaceChildren(el('option', { value: '' }, 'nothing'),
      ...others.map((j) => el('option', { value: j.id }, `#${j.id} · ${jobScene(j)} · ${jobVariants(j)}`)));
    select.value = others.some((j) => j.id === current) ? current : '';
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

  /** A finished job's figures, written by the server (GET /api/jobs/ID/values). */
  async function values(id) {
    let v = state.values.get(id);
    if (!v) {
      v = await api('GET', `/api/jobs/${encodeURIComponent(id)}/values`);
      if (!v || typeof v !== 'object') throw new Error('the figures are empty');
      state.values.set(id, v);
    }
    return v;
  }

  async function loadResults(job) {
    const box = $('results');
    const beside = state.besideId ? jobById(state.besideId) : null;
    if (!state.values.has(job.id)) box.replaceChildren(el('p', { class: 'muted placeholder' }, 'Loading results…'));
    let mine;
    let theirs = null;
    try {
      mine = await values(job.id);
      if (beside) theirs = await values(beside.id);
    } catch (err) {
      if (state.selectedId === job.id) {
        state.viewKey = null;
        box.replaceChildren(el('p', { class: 'error-box' }, `Cannot load the results: ${err.message}`));
      }
      reportError(err, `Results of job #${job.id}`);
      return;
    }
    if (state.selectedId !== job.id) return;
    try {
      if (theirs) {
        box.replaceChildren(el('div', { class: 'side-by-side' },
          el('div', { class: 'side' }, el('h3', { class: 'side-title' }, `Job #${job.id}`), ...renderResults(job, mine)),
          el('div', { class: 'side' }, el('h3', { class: 'side-title' }, `Job #${beside.id}`), ...renderResults(beside, theirs))));
      } else {
        box.replaceChildren(...renderResults(job, mine));
      }
    } catch (err) {
      box.replaceChildren(el('p', { class: 'error-box' }, `Cannot show the results: ${err.message}`));
      console.error(err);
    }
  }

  /** The blocks of one job's results. */
  function renderResults(job, v) {
    const scenes = Array.isArray(v.scenes) ? v.scenes : [];
    const blocks = [];
    if (v.failures?.length) {
      blocks.push(el('section', { class: 'result-block failures' },
        el('h3', {}, v.failures_title),
        el('p', { class: 'hint' }, 'These parts of the run failed; the rest of the results stand.'),
        el('ul', {}, v.failures.map((f) => el('li', {}, el('strong', {}, f.place), ': ', f.message)))));
    }
    const sceneBox = el('div', { class: 'scene-results' });
    if (scenes.length > 1) {
      const picker = el('select', { class: 'result-scene' },
        scenes.map((sc, i) => el('option', { value: String(i) }, sc.option)));
      picker.addEventListener('change', () => {
        const i = Number(picker.value);
        sceneBox.replaceChildren(...renderScene(job, scenes[i] ?? scenes[0], i));
      });
      blocks.push(el('label', { class: 'field scene-picker' }, v.scene_picker, picker));
    }
    blocks.push(sceneBox);
    if (scenes.length) sceneBox.replaceChildren(...renderScene(job, scenes[0], 0));
    else sceneBox.replaceChildren(el('p', { class: 'muted' }, 'The run has no scenes.'));
    if (v.profile) blocks.push(renderProfile(job, v.profile));
    return blocks;
  }

  function block(title, detail, ...children) {
    return el('section', { class: 'result-block' },
      el('h3', {}, title, detail ? el('span', { class: 'detail' }, detail) : null),
      ...children);
  }

  function renderScene(job, scene, index) {
    const out = [el('div', { class: 'scene-summary' },
      el('h3', {}, scene.name),
      el('span', { class: 'detail' }, scene.summary))];
    const variants = scene.variants ?? [];
    if (variants.length) {
      out.push(renderImages(job, scene, variants, index));
      const heat = renderHeatMaps(job, scene, variants);
      if (heat) out.push(heat);
      const compare = renderCompare(job, scene, variants);
      if (compare) out.push(compare);
      out.push(renderCounts(scene.counts));
    } else {
      out.push(el('p', { class: 'muted' }, 'No variant ran on this scene.'));
    }
    if (scene.pixel_maps?.length) out.push(renderPixelMaps(job, scene, index));
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

  /**
   * An image that opens in the zoom viewer when clicked, and, when the scene has
   * per-pixel maps, reads the counts under the pointer.
   */
  function viewableImage(job, scene, index, src, alt, cls) {
    const img = pixelImage(src, alt, scene, cls);
    const button = el('button', { type: 'button', class: 'image-button', title: 'Zoom and pan (click)' }, img);
    button.addEventListener('click', () => openViewer(job, scene, index, src, alt));
    if (scene.pixel_maps?.length) attachPixelReadout(img, job, index);
    return button;
  }

  function renderImages(job, scene, variants, index) {
    const grid = el('div', { class: 'image-grid' });
    for (const v of variants) {
      grid.append(el('figure', { class: `variant-image${v.reference ? ' reference' : ''}` },
        v.image
          ? viewableImage(job, scene, index, fileUrl(job.id, v.image), `${v.variant} render of ${scene.name}`)
          : el('div', { class: 'missing' }, 'no image'),
        el('figcaption', {},
          el('span', { class: 'cap-title' }, v.variant),
          el('span', { class: 'cap-line median', title: v.interval ? `interval ${v.interval}` : null },
            `median ${v.median}`),
          el('span', { class: 'cap-line' },
            v.reference
              ? 'reference'
              : v.not_comparable
                // An outside tracer that drew another picture: its time is no comparison.
                ? el('span', { class: 'muted', title: v.not_comparable }, `not comparable: ${v.not_comparable}`)
                : v.speedup
                  ? el('span', { class: `speedup ${v.faster ? 'faster' : 'slower'}`, title: v.speedup_title }, `${v.speedup} vs baseline`)
                  : 'speed-up unknown',
            v.verdict && !v.not_comparable ? el('span', { class: 'muted' }, ` (${v.verdict})`) : null),
          v.time_covers
            ? el('span', { class: 'cap-line muted' }, `its time covers ${v.time_covers}`)
            : null,
          v.quality
            ? el('span', { class: 'cap-line' }, bandChip(v.quality.band), ` ${v.quality.rms}`)
            : el('span', { class: 'cap-line muted' }, v.reference ? 'the reference image' : 'no quality figures'))));
    }
    const hint = scene.pixel_maps?.length
      ? 'side by side; click an image to zoom, hover it to read its per-pixel counts'
      : 'side by side; click an image to zoom and pan';
    return block('Images', hint, grid, scene.pixel_maps?.length ? el('div', { class: 'pixel-readout', 'aria-live': 'polite' }) : null);
  }

  function renderHeatMaps(job, scene, variants) {
    const withMaps = variants.filter((v) => v.heat_map);
    if (!withMaps.length) return null;
    const grid = el('div', { class: 'image-grid' }, withMaps.map((v) => el('figure', { class: 'heat-figure' },
      viewableImage(job, scene, null, fileUrl(job.id, v.heat_map), `difference of ${v.variant} from baseline`, 'heat-map'),
      el('figcaption', {},
        el('span', { class: 'cap-title' }, `${v.variant} − baseline`),
        v.quality
          ? [
            el('span', { class: 'cap-line' }, bandChip(v.quality.band), ` ${v.quality.rms}`),
            el('span', { class: 'cap-line muted' }, v.quality.detail),
          ]
          : null))));
    return block('Difference heat maps', 'per-pixel difference from baseline', grid);
  }

  function renderCompare(job, scene, variants) {
    const withImages = variants.filter((v) => v.image);
    if (withImages.length < 2) return null;
    const options = () => withImages.map((v) => el('option', { value: v.variant }, v.variant));
    const selectA = el('select', { class: 'compare-a', 'aria-label': 'Image A' }, options());
    const selectB = el('select', { class: 'compare-b', 'aria-label': 'Image B' }, options());
    const a0 = withImages.find((v) => v.reference) ?? withImages[0];
    const b0 = withImages.find((v) => v !== a0) ?? withImages[1];
    selectA.value = a0.variant;
    selectB.value = b0.variant;

    const imgA = el('img', { class: 'compare-img compare-img-a', alt: '', draggable: 'false' });
    const imgB = el('img', { class: 'compare-img compare-img-b', alt: '', draggable: 'false' });
    const divider = el('div', { class: 'compare-divider', 'aria-hidden': 'true' });
    const labelB = el('span', { class: 'compare-label compare-label-b' });
    const labelA = el('span', { class: 'compare-label compare-label-a' });
    const stage = el('div', {
      class: 'compare-stage',
      style: { aspectRatio: `${scene.width} / ${scene.height}` },
    }, imgA, imgB, divider, labelB, labelA);

    const slider = el('input', {
      type: 'range', class: 'compare-slider', min: '0', max: '100', step: '1', value: '50',
      'aria-label': 'How much of image B covers image A (from the left)',
    });
    const toggle = el('button', { type: 'button', class: 'small compare-toggle' }, 'Toggle A / B');

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
      slider.value = String(Math.min(1, Math.max(0, (ev.clientX - rect.left) / rect.width)) * 100);
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

    return block('Compare', 'B revealed over A: drag on the picture or the slider',
      el('div', { class: 'compare-controls' },
        el('label', { class: 'field' }, 'A', selectA),
        el('label', { class: 'field' }, 'B', selectB),
        el('label', { class: 'field grow' }, 'Reveal B', slider),
        toggle),
      el('div', { class: 'compare-wrap' }, stage));
  }

  function renderCounts(counts) {
    if (!counts?.rows?.length) return block('Counts', null, el('p', { class: 'muted' }, 'No counts.'));
    const table = el('table', { class: 'data counts-table' },
      el('thead', {}, el('tr', {},
        el('th', { scope: 'col' }, 'counter'),
        counts.variants.map((v) => el('th', { scope: 'col', class: 'num' }, v)))),
      el('tbody', {}, counts.rows.map((row) => el('tr', {},
        el('th', { scope: 'row' }, el('code', {}, row.key)),
        row.cells.map((c) => el('td', { class: `num tone-${cssPart(c.tone)}`, title: c.title }, c.text))))));
    return block('Counts', 'exact, per render; green fewer / red more than baseline; work baseline does not do is not coloured',
      el('div', { class: 'table-wrap' }, table));
  }

  function renderPixelMaps(job, scene, index) {
    const children = [];
    for (const set of scene.pixel_maps) {
      children.push(el('h4', {}, set.variant, el('span', { class: 'detail' }, set.detail)));
      children.push(el('div', { class: 'map-grid' }, set.maps.map((m) => {
        const src = fileUrl(job.id, joinPath(set.directory, m.png));
        return el('figure', { class: 'pixel-map', title: m.description },
          // A map's picture carries its legend: no pixel read-out on it (the
          // renders above read the same maps).
          viewableImage(job, { ...scene, width: null, height: null, pixel_maps: [] }, null, src, `${m.key} per sample`),
          el('figcaption', {},
            el('span', { class: 'cap-title' }, el('code', {}, m.key)),
            el('span', { class: 'cap-line muted' }, m.unit),
            el('span', { class: 'cap-line' }, m.stats)));
      })));
    }
    return block('Per-pixel maps', 'false colour, one value per sample; click to zoom', ...children);
  }

  function renderHardware(job, hw, scene) {
    const rows = [
      ...hw.rows.map(([k, v]) => [k, v]),
      ['Fits the device', el('span', { class: `badge ${hw.fits ? 'status-done' : 'status-failed'}` }, hw.fits ? 'yes' : 'no')],
      ['Emulator vs software', [bandChip(hw.emulator_band), ` ${hw.emulator_rms}`]],
    ];
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
      el('figcaption', {}, caption, ' · ',
        el('a', { href: url, target: '_blank', rel: 'noopener' }, 'open alone')),
      el('object', { type: 'image/svg+xml', data: url, class: 'flame-svg', 'aria-label': caption },
        el('a', { href: url, target: '_blank', rel: 'noopener' }, `Open ${caption}`)));
  }

  function renderProfile(job, profile) {
    const children = profile.flames.map((f) => flame(job, f.svg, f.caption));
    if (profile.speedscope?.length) {
      children.push(el('p', { class: 'hint speedscope' },
        'Open in speedscope: download ',
        profile.speedscope.map(([variant, file], i) => [i ? ' or ' : '',
          el('a', { href: fileUrl(job.id, file), download: `rtprof-job-${job.id}-speedscope-${variant}.json` }, `${variant}'s profile`)]),
        ' and drop it on speedscope.app (or open it in the Firefox Profiler); the page itself links to no other site.'));
    }
    if (profile.flat?.length) {
      children.push(el('h4', {}, profile.flat_title, el('span', { class: 'detail' }, profile.flat_detail)));
      children.push(el('div', { class: 'table-wrap' }, el('table', { class: 'data flat-table' },
        el('thead', {}, el('tr', {},
          el('th', { scope: 'col' }, 'function'),
          el('th', { scope: 'col', class: 'num' }, 'self %'),
          el('th', { scope: 'col', class: 'num' }, 'self time'),
          el('th', { scope: 'col', class: 'num' }, 'calls'))),
        el('tbody', {}, profile.flat.map((row) => el('tr', { class: row.noise ? 'noise' : null },
          el('td', { class: 'fn' }, el('code', {}, row.name)),
          el('td', { class: 'num' }, row.percent),
          el('td', { class: 'num' }, row.self_seconds),
          el('td', { class: 'num' }, row.calls)))))));
    }
    return block('Profile', profile.detail, ...children);
  }

  // ---------------------------------------------------------------- pixel read-out and zoom

  /** Reads the per-pixel maps under the pointer (one request at a time). */
  function attachPixelReadout(img, job, index) {
    if (index == null) return;
    let busy = false;
    let pending = null;
    const readout = () => img.closest('.result-block')?.querySelector('.pixel-readout')
      ?? $('viewer-readout');
    async function ask(x, y) {
      if (busy) {
        pending = [x, y];
        return;
      }
      busy = true;
      try {
        const v = await api('GET', `/api/jobs/${encodeURIComponent(job.id)}/pixel?scene=${index}&x=${x}&y=${y}`);
        const box = readout();
        if (box) {
          box.replaceChildren(el('strong', {}, v.position),
            ...v.variants.map((set) => el('span', { class: 'readout-set' },
              el('span', { class: 'readout-variant' }, set.variant),
              set.values.map(([k, value]) => el('span', { class: 'readout-value' }, el('code', {}, k), ' ', value)))));
        }
      } catch (_) {
        // A failed read-out is not worth a message: the next move asks again.
      } finally {
        busy = false;
        if (pending) {
          const [px, py] = pending;
          pending = null;
          ask(px, py);
        }
      }
    }
    img.addEventListener('mousemove', (ev) => {
      const rect = img.getBoundingClientRect();
      if (rect.width <= 0 || !img.naturalWidth) return;
      // The picture inside the element's box (object-fit: contain letterboxes it).
      const fit = Math.min(rect.width / img.naturalWidth, rect.height / img.naturalHeight);
      const left = rect.left + (rect.width - img.naturalWidth * fit) / 2;
      const top = rect.top + (rect.height - img.naturalHeight * fit) / 2;
      const x = Math.floor((ev.clientX - left) / fit);
      const y = Math.floor((ev.clientY - top) / fit);
      if (x >= 0 && y >= 0 && x < img.naturalWidth && y < img.naturalHeight) ask(x, y);
    });
  }

  /** The zoom viewer: wheel or +/- to zoom, drag or arrows to pan, 0 to fit, Esc to close. */
  function openViewer(job, scene, index, src, alt) {
    const dialog = $('viewer');
    const img = $('viewer-image');
    const view = { scale: 1, x: 0, y: 0 };
    img.src = src;
    img.alt = alt;
    $('viewer-title').textContent = alt;
    $('viewer-readout').replaceChildren();
    const fresh = img.cloneNode(false);
    img.replaceWith(fresh);
    fresh.id = 'viewer-image';
    if (scene.pixel_maps?.length && index != null) attachPixelReadout(fresh, job, index);
    const zoom = (factor) => {
      view.scale = Math.min(64, Math.max(1, view.scale * factor));
      if (view.scale === 1) { view.x = 0; view.y = 0; }
      fresh.style.transform = `translate(${view.x}px, ${view.y}px) scale(${view.scale})`;
    };
    const stage = $('viewer-stage');
    stage.onwheel = (ev) => {
      ev.preventDefault();
      zoom(ev.deltaY < 0 ? 1.25 : 0.8);
    };
    let drag = null;
    stage.onpointerdown = (ev) => {
      drag = { x: ev.clientX - view.x, y: ev.clientY - view.y };
      stage.setPointerCapture(ev.pointerId);
    };
    stage.onpointermove = (ev) => {
      if (!drag) return;
      view.x = ev.clientX - drag.x;
      view.y = ev.clientY - drag.y;
      fresh.style.transform = `translate(${view.x}px, ${view.y}px) scale(${view.scale})`;
    };
    stage.onpointerup = () => { drag = null; };
    dialog.onkeydown = (ev) => {
      const step = 40;
      if (ev.key === '+' || ev.key === '=') zoom(1.25);
      else if (ev.key === '-') zoom(0.8);
      else if (ev.key === '0') { view.scale = 1; view.x = 0; view.y = 0; zoom(1); }
      else if (ev.key === 'ArrowLeft') { view.x += step; zoom(1); }
      else if (ev.key === 'ArrowRight') { view.x -= step; zoom(1); }
      else if (ev.key === 'ArrowUp') { view.y += step; zoom(1); }
      else if (ev.key === 'ArrowDown') { view.y -= step; zoom(1); }
      else return;
      ev.preventDefault();
    };
    $('viewer-in').onclick = () => zoom(1.25);
    $('viewer-out').onclick = () => zoom(0.8);
    $('viewer-fit').onclick = () => { view.scale = 1; view.x = 0; view.y = 0; zoom(1); };
    zoom(1);
    dialog.showModal();
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
    if (job) json.setAttribute('download', `rtprof-job-${job.id}-results.json`);
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

  let gateKey = null;

  function renderGateSelects() {
    const done = state.jobs.filter((j) => j.status === 'done');
    // Rebuilt only when the finished jobs change (not under a user's open list).
    const key = done.map((j) => j.id).join(',');
    if (key === gateKey) return;
    gateKey = key;
    const oldSel = $('gate-old');
    const newSel = $('gate-new');
    const prevOld = oldSel.value;
    const prevNew = newSel.value;
    const options = () => done.map((j) => el('option', { value: j.id },
      `#${j.id} · ${jobScene(j)} · ${jobVariants(j)} · ${j.text?.created ?? ''}`));
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
        saveForm();
        updateEstimate();
      });
    }
    $('run-button').addEventListener('click', startRun);
    $('cancel-button').addEventListener('click', cancelJob);
    $('rerun-button').addEventListener('click', rerunJob);
    $('delete-button').addEventListener('click', deleteJob);
    $('beside-select').addEventListener('change', (ev) => {
      state.besideId = ev.target.value || null;
      const job = jobById(state.selectedId);
      if (job) updateView(job);
    });
    $('viewer-close').addEventListener('click', () => $('viewer').close());
    $('panel-run').addEventListener('change', saveForm);
    for (const id of ['width', 'height', 'threads']) {
      $(id).addEventListener('input', () => {
        saveForm();
        updateEstimate();
      });
    }
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
    restoreForm();
    updateEstimate();
    if (hash.job) selectJob(hash.job, {});
    setInterval(poll, POLL_MS);
  }

  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', init);
  else init();
})();
