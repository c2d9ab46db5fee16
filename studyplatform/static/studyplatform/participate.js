/* The participant's page: preload clips, own clip controls, save each answer as soon as
 * it is given (retrying through a lost connection), log media events in batches, and
 * move on without double submits. Without this script the page still works: native
 * video controls and a plain form post. */
(function () {
  "use strict";
  const form = document.getElementById("page-form");
  if (!form) { return; }
  const csrf = form.querySelector("[name=csrfmiddlewaretoken]").value;
  const page = Number(form.dataset.page);
  const trial = form.dataset.trial;
  const replayLimit = form.dataset.replayLimit ? Number(form.dataset.replayLimit) : null;
  const fullView = form.dataset.fullView === "1";
  const status = document.getElementById("save-status");
  const pageError = document.getElementById("page-error");
  const nextButton = document.getElementById("next-button");
  let shownAt = performance.now();
  /* Text in the study's language: Django's JavaScript catalogue (jsi18n), loaded before
   * this script, defines gettext; without it the English message ids are shown. */
  const _ = window.gettext || function (text) { return text; };
  const ngettext = window.ngettext || function (one, many, n) { return n === 1 ? one : many; };
  const fmt = function (text, values) {
    return window.interpolate ? window.interpolate(text, values, true)
      : text.replace(/%\((\w+)\)s/g, function (all, name) { return values[name]; });
  };

  /* Time limit: count the server's "seconds left" down in whole minutes; at the end,
   * reload, and the server says the time is up. When little time is left (the server
   * says how little), the timer turns prominent and says so once to screen readers. */
  const timer = document.getElementById("time-left");
  if (timer) {
    const endsAt = performance.now() + Number(timer.dataset.secondsLeft) * 1000;
    const lowSeconds = Number(timer.dataset.lowSeconds);
    let warned = timer.classList.contains("time-low");
    const say = function (minutes) {
      return minutes < 1 ? _("Less than a minute left")
        : fmt(ngettext("%(minutes)s minute left", "%(minutes)s minutes left", minutes), {minutes: minutes});
    };
    const tick = function () {
      const seconds = Math.max(0, Math.round((endsAt - performance.now()) / 1000));
      timer.textContent = say(Math.floor(seconds / 60));
      if (seconds < lowSeconds && !warned) {
        warned = true;
        timer.classList.add("time-low");
        status.textContent = say(Math.round(lowSeconds / 60)) + ".";
      }
      if (seconds === 0) { window.location.reload(); return; }
      setTimeout(tick, 1000);
    };
    tick();
  }

  /* ASL first: English text is secondary, and can be hidden where an ASL video signs it. */
  const englishToggle = document.getElementById("english-toggle");
  if (englishToggle) {
    const hideKey = "signstudy-hide-english";
    const apply = function (hidden) {
      document.body.classList.toggle("hide-english", hidden);
      englishToggle.setAttribute("aria-pressed", String(hidden));
      englishToggle.textContent = hidden ? _("Show the written text") : _("Hide the written text");
    };
    apply(localStorage.getItem(hideKey) === "1");
    englishToggle.hidden = false;
    englishToggle.addEventListener("click", function () {
      const hidden = !document.body.classList.contains("hide-english");
      try { localStorage.setItem(hideKey, hidden ? "1" : "0"); } catch (e) { /* private mode */ }
      apply(hidden);
    });
  }

  function sleep(ms) { return new Promise(function (resolve) { setTimeout(resolve, ms); }); }
  function backoff(attempt) { return Math.min(500 * Math.pow(2, attempt), 8000); }
  function setStatus(text) { status.textContent = text; }
  function post(url, body, keepalive) {
    return fetch(url, {
      method: "POST", credentials: "same-origin", keepalive: Boolean(keepalive),
      headers: {"Content-Type": "application/json", "Accept": "application/json", "X-CSRFToken": csrf},
      body: JSON.stringify(body),
    });
  }

  /* Events: kept in localStorage until the server has them, so a reload or a lost
   * connection loses none; the server skips a batch it already logged. */
  const queueKey = "signstudy-events-" + form.dataset.token;
  let queue = [];
  try { queue = JSON.parse(localStorage.getItem(queueKey) || "[]"); } catch (e) { queue = []; }
  let lastTime = 0;
  function store() { try { localStorage.setItem(queueKey, JSON.stringify(queue)); } catch (e) { /* full or private mode: keep in memory */ } }
  function log(kind, clip, mediaTime, detail) {
    lastTime = Math.max(Date.now(), lastTime + 1);  // distinct times: the server's duplicate key
    queue.push({kind: kind, page: page, clip: clip || null,
      media_time_s: mediaTime === undefined ? null : Math.round(mediaTime * 1000) / 1000,
      client_time_ms: lastTime, detail: detail || {}});
    store();
  }
  /* A batch the server fails on (5xx) is retried with backoff; after two failures it is
   * halved, and a single event that still fails goes to the back of the queue, so one
   * event the server cannot take never holds back those behind it, and a server that is
   * down loses nothing. A 4xx batch will never be taken (e.g. from an old page). */
  const BATCH_EVENTS = 200;
  let batchSize = BATCH_EVENTS, failures = 0, rounds = 0, flushing = null;
  function flush(keepalive) {
    if (flushing) { return flushing; }
    if (!queue.length) { return Promise.resolve(true); }
    const batch = queue.slice(0, batchSize);
    flushing = post(form.dataset.eventsUrl, {events: batch}, keepalive).then(function (response) {
      if (response.ok || (response.status >= 400 && response.status < 500)) {
        queue = queue.slice(batch.length);
        store();
        batchSize = BATCH_EVENTS;
        failures = rounds = 0;
        return true;
      }
      rounds++;
      if (++failures >= 2) {
        failures = 0;
        if (batch.length > 1) {
          batchSize = Math.ceil(batch.length / 2);
        } else {
          queue.push(queue.shift());
          store();
          batchSize = BATCH_EVENTS;
        }
      }
      setTimeout(flush, backoff(rounds));
      return false;
    }).catch(function () { return false; }).finally(function () { flushing = null; });
    return flushing;
  }
  setInterval(flush, 4000);
  document.addEventListener("visibilitychange", function () {
    if (document.visibilityState === "hidden") { log("page_hidden"); flush(true); }
  });

  /* Answers: one request at a time per question, the latest value wins. */
  const pending = new Map();
  const inflight = new Set();
  function showQuestionError(question, message) {
    const element = document.getElementById("error-" + question);
    if (!element) { return; }
    element.textContent = message || "";
    element.hidden = !message;
  }
  /* A lost connection is retried until it is back; a server error (5xx) a few times, then
   * the answer waits for the page's Next, which sends every answer again. */
  const SERVER_ERROR_ATTEMPTS = 5;
  const unsaved = new Set();
  const sending = new Map();  // question → its send loop, until the loop ends
  function send(question) {
    if (!sending.has(question)) {
      sending.set(question, sendLoop(question).finally(function () { sending.delete(question); }));
    }
    return sending.get(question);
  }
  async function sendLoop(question) {
    if (inflight.has(question)) { return; }
    inflight.add(question);
    for (let attempt = 0, serverErrors = 0; pending.has(question); attempt++) {
      const payload = pending.get(question);
      setStatus(_("Saving…"));
      let retry = "";
      try {
        const response = await post(form.dataset.answerUrl, payload);
        if (response.ok) {
          showQuestionError(question, "");
          unsaved.delete(question);
        } else if (response.status < 500) {
          const data = await response.json().catch(function () { return {}; });
          showQuestionError(question, data.error || _("This answer could not be saved."));
          unsaved.add(question);
        } else if (++serverErrors >= SERVER_ERROR_ATTEMPTS) {
          showQuestionError(question, _("The server could not save this answer now; it is sent again when you go on."));
          unsaved.add(question);
        } else { retry = _("server error"); }
      } catch (e) { retry = _("no connection"); }
      if (retry) {
        setStatus(fmt(_("Not saved yet (%(reason)s). Trying again…"), {reason: retry}));
        await sleep(backoff(attempt));
      } else if (pending.get(question) === payload) {
        pending.delete(question);
      }
    }
    inflight.delete(question);
    if (!pending.size && !inflight.size) {
      setStatus(unsaved.size ? _("Some answers are not saved yet.") : _("Answer saved."));
    }
  }
  function answered(input) {
    const match = /^q-(.+)$/.exec(input.name || "");
    if (!match) { return; }
    const question = match[1];
    const rt = Math.round(performance.now() - shownAt);
    const given = Date.now();  // the media events' clock: the quality columns compare them
    const rtInput = form.querySelector('[name="rt-' + question + '"]');
    if (rtInput) { rtInput.value = String(rt); }
    const givenInput = form.querySelector('[name="client-' + question + '"]');
    if (givenInput) { givenInput.value = String(given); }
    pending.set(question, {page: page, trial: trial, question: question, value: input.value,
                           rt_ms: rt, client_ms: given});
    send(question);
  }
  form.addEventListener("change", function (event) { answered(event.target); });

  /* Sliders start untouched, with no name: the page sends nothing for them, so an
   * untouched slider is an unanswered question, not an answer at its starting point.
   * Moving it, or tapping it where it stands, gives it its name and answers. */
  function touchSlider(input) {
    const output = form.querySelector('output[for="' + input.id + '"]');
    if (output) { output.textContent = input.value; }
    if (input.name) { return; }
    input.name = input.dataset.name;
    input.closest(".slider").classList.remove("untouched");
    answered(input);
  }
  form.querySelectorAll('.slider input[type="range"][data-name]').forEach(function (input) {
    ["input", "pointerup", "keyup"].forEach(function (type) {
      input.addEventListener(type, function () { touchSlider(input); });
    });
  });

  /* Next / Previous: post the form by script, retrying through a lost connection; the
   * server ignores a repeated move, so a double click changes nothing. */
  let moving = false;
  form.addEventListener("submit", async function (event) {
    event.preventDefault();
    if (moving) { return; }
    const nav = event.submitter && event.submitter.value === "back" ? "back" : "next";
    moving = true;
    form.querySelectorAll(".page-nav button").forEach(function (b) { b.disabled = true; });
    pageError.hidden = true;
    await flush();
    // A save still on its way would reach the server after this page's form and put an
    // older answer over the one the form carries; the page would be gone before the
    // newer save was sent. Let the saves in flight (and their newer values) land first.
    await Promise.all(Array.from(sending.values()));
    const data = new FormData(form);
    data.set("nav", nav);
    for (let attempt = 0, serverErrors = 0; ; attempt++) {
      try {
        const response = await fetch(form.action || location.href, {
          method: "POST", body: data, credentials: "same-origin",
          headers: {"Accept": "application/json", "X-CSRFToken": csrf},
        });
        const body = await response.json().catch(function () { return {}; });
        if (response.ok && body.url) { location.assign(body.url); return; }
        if (response.status < 500) {
          pageError.textContent = body.error || _("This page could not be saved.");
          pageError.hidden = false;
          Object.entries(body.questions || {}).forEach(function (entry) {
            showQuestionError(entry[0], entry[1]);
          });
          const first = form.querySelector(".question-error:not([hidden])");
          (first ? first.closest("fieldset").querySelector("input, textarea") : pageError).focus?.();
          break;
        }
        if (++serverErrors >= SERVER_ERROR_ATTEMPTS) {
          pageError.textContent = _("The server could not save this page just now. Your answers are kept; please press the button again in a moment.");
          pageError.hidden = false;
          break;
        }
      } catch (e) { /* no connection: retry below */ }
      setStatus(_("Not saved yet. Trying again…"));
      await sleep(backoff(attempt));
    }
    moving = false;
    form.querySelectorAll(".page-nav button").forEach(function (b) { b.disabled = false; });
  });

  /* Signed answers: record with the webcam, watch, record again, then send in chunks
   * that resume where the server stopped after a lost connection. Each recording (take)
   * has its own id, so the server never joins one take's bytes to another's, and the
   * last chunk says the whole file's SHA-256 and how long the recording ran. */
  const CHUNK_BYTES = 256 * 1024;
  // Seconds the camera shows the signer before a recording starts, counted down.
  const COUNTDOWN_S = 3;
  function newTakeId() {
    if (window.crypto && crypto.randomUUID) { return crypto.randomUUID(); }
    const b = crypto.getRandomValues(new Uint8Array(16));
    b[6] = (b[6] & 0x0f) | 0x40; b[8] = (b[8] & 0x3f) | 0x80;
    const h = Array.from(b, function (x) { return x.toString(16).padStart(2, "0"); }).join("");
    return h.slice(0, 8) + "-" + h.slice(8, 12) + "-" + h.slice(12, 16) + "-" + h.slice(16, 20) + "-" + h.slice(20);
  }
  async function sha256Hex(blob) {
    const digest = await crypto.subtle.digest("SHA-256", await blob.arrayBuffer());
    return Array.from(new Uint8Array(digest), function (x) { return x.toString(16).padStart(2, "0"); }).join("");
  }
  function makeButton(text) {
    const element = document.createElement("button");
    element.type = "button";
    element.className = "button secondary";
    element.textContent = text;
    return element;
  }
  form.querySelectorAll(".signed-answer").forEach(function (box) {
    const preview = box.querySelector(".signed-preview");
    const controls = box.querySelector(".signed-controls");
    const state = box.querySelector(".signed-status");
    const url = box.dataset.uploadUrl;
    if (!window.MediaRecorder || !navigator.mediaDevices) {
      state.textContent = _("This browser cannot record video here; please type your answer.");
      return;
    }
    const record = makeButton(preview.getAttribute("src") ? _("Record again") : _("Record a signed answer"));
    const stop = makeButton(_("Stop recording"));
    const send = makeButton(_("Send this recording"));
    stop.hidden = send.hidden = true;
    controls.append(record, stop, send);
    let recorder = null;
    let blob = null;
    let take = "", startedAt = 0, durationMs = 0, clock = null;
    record.addEventListener("click", async function () {
      let stream;
      try {
        stream = await navigator.mediaDevices.getUserMedia({video: true, audio: false});
      } catch (error) {
        state.textContent = fmt(_("The camera could not be used (%(error)s). Allow it, or type your answer."), {error: error.name});
        return;
      }
      const parts = [];
      preview.hidden = false;
      preview.controls = false;
      preview.removeAttribute("src");
      preview.srcObject = stream;
      preview.play().catch(function () {});
      recorder = new MediaRecorder(stream);
      recorder.ondataavailable = function (event) { if (event.data.size) { parts.push(event.data); } };
      recorder.onstop = function () {
        clearInterval(clock);  // however it stopped: the button, or the camera ending
        stream.getTracks().forEach(function (track) { track.stop(); });
        blob = new Blob(parts, {type: recorder.mimeType || "video/webm"});
        preview.srcObject = null;
        preview.src = URL.createObjectURL(blob);
        preview.controls = true;
        record.textContent = _("Record again");
        record.hidden = false;
        stop.hidden = true;
        send.hidden = false;
        send.focus();
        state.textContent = _("Watch your recording, then send it or record again.");
      };
      take = newTakeId();
      record.hidden = send.hidden = true;
      // The camera shows the signer first and a countdown says when recording starts:
      // without it, the first second of the answer was signed before the camera ran.
      await Promise.race([
        new Promise(function (resolve) { preview.onplaying = resolve; if (!preview.paused) { resolve(); } }),
        sleep(3000),  // a preview that never plays must not keep the recording from starting
      ]);
      for (let left = COUNTDOWN_S; left > 0; left--) {
        state.textContent = fmt(_("Recording starts in %(seconds)s…"), {seconds: left});
        await sleep(1000);
      }
      recorder.start(500);
      startedAt = Date.now();
      stop.hidden = false;
      stop.focus();
      const shown = function () {
        const seconds = Math.floor((Date.now() - startedAt) / 1000);
        state.textContent = fmt(_("Recording… %(time)s"), {time: Math.floor(seconds / 60) + ":" + String(seconds % 60).padStart(2, "0")});
      };
      shown();
      clock = setInterval(shown, 250);
    });
    stop.addEventListener("click", function () {
      // Measured here, not when the stop event arrives (late on a busy page).
      if (recorder && recorder.state !== "inactive") { durationMs = Date.now() - startedAt; recorder.stop(); }
    });
    send.addEventListener("click", async function () {
      send.disabled = record.disabled = true;
      const digest = await sha256Hex(blob);
      const takeUrl = url + "?take=" + encodeURIComponent(take);
      let offset = 0;
      for (let attempt = 0; ;) {
        const end = Math.min(offset + CHUNK_BYTES, blob.size);
        const final = end >= blob.size;
        const headers = {"X-CSRFToken": csrf, "X-Upload-Take": take, "X-Upload-Offset": String(offset),
          "X-Upload-Final": final ? "1" : "0", "Content-Type": "application/octet-stream",
          "Accept": "application/json"};
        if (final) {
          headers["X-Upload-Sha256"] = digest;
          headers["X-Upload-Duration-Ms"] = String(durationMs);
        }
        let retry = false;
        try {
          const response = await fetch(url, {
            method: "POST", credentials: "same-origin", body: blob.slice(offset, end), headers: headers,
          });
          const data = await response.json().catch(function () { return {}; });
          if (response.ok) {
            offset = data.offset;
            attempt = 0;
            if (data.saved) { break; }
            state.textContent = fmt(_("Sending… %(percent)s"), {percent: Math.round(100 * offset / blob.size) + " %"});
          } else if (response.status === 409) {
            offset = data.offset;
          } else if (response.status < 500) {
            state.textContent = data.error || _("The recording could not be saved.");
            send.disabled = record.disabled = false;
            return;
          } else { retry = true; }
        } catch (error) { retry = true; }
        if (retry) {
          state.textContent = _("Connection lost. The recording keeps sending when it is back…");
          await sleep(backoff(attempt++));
          try {
            const where = await fetch(takeUrl, {credentials: "same-origin", headers: {"Accept": "application/json"}});
            if (where.ok) { offset = (await where.json()).offset; }
          } catch (error) { /* still offline: try again */ }
        }
      }
      state.textContent = _("Your signed answer is saved.");
      send.hidden = true;
      record.disabled = false;
    });
  });

  /* Clips: preload before the page shows, own Play/Replay button, play count, events. */
  const figures = Array.from(form.querySelectorAll("figure.clip"));
  const watched = new Set((form.dataset.watched || "").split(",").filter(Boolean).map(Number));
  const questionSets = Array.from(form.querySelectorAll("fieldset.question"));
  const fullViewNote = document.getElementById("full-view-note");
  function updateFullView() {
    if (!fullView) { return; }
    const done = figures.every(function (f) { return watched.has(Number(f.dataset.clip)); });
    questionSets.forEach(function (set) { set.disabled = !done; });
    fullViewNote.hidden = done;
  }
  figures.forEach(function (figure) {
    const video = figure.querySelector("video");
    const controls = figure.querySelector(".clip-controls");
    if (!video) { return; }
    const clip = Number(figure.dataset.clip);
    const label = figure.querySelector("figcaption").textContent;
    let plays = 0;
    /* Own controls instead of the browser's bar: one tab stop per clip. The button
     * plays, pauses and replays (Space or Enter); arrow keys move a second back or on,
     * Home goes to the start; the state is announced. A thin bar shows the position
     * and takes a click. Seeking is off when plays are limited. */
    video.controls = false;
    video.tabIndex = -1;
    const button = document.createElement("button");
    button.type = "button";
    button.className = "button play-button";
    button.setAttribute("aria-describedby", "clip-keys-hint");
    const count = document.createElement("span");
    count.className = "play-count";
    count.setAttribute("aria-live", "polite");
    const bar = document.createElement("div");
    bar.className = "clip-progress";
    bar.setAttribute("aria-hidden", "true");
    const fill = document.createElement("div");
    fill.className = "clip-progress-fill";
    bar.append(fill);
    controls.append(bar, button, count);
    let announced = "";
    function seconds(t) { return (Math.round(t * 10) / 10).toFixed(1); }
    function refresh() {
      const left = replayLimit === null ? null : replayLimit - plays;
      if (!video.paused && !video.ended) { button.textContent = fmt(_("Pause %(clip)s"), {clip: label}); }
      else if (plays && left !== null && left <= 0) { button.textContent = _("No plays left"); }
      else { button.textContent = fmt(plays ? _("Replay %(clip)s") : _("Play %(clip)s"), {clip: label}); }
      button.disabled = video.paused && left !== null && left <= 0;
      let state = video.ended ? fmt(_("%(clip)s ended"), {clip: label})
        : !video.paused ? fmt(_("%(clip)s playing"), {clip: label})
        : plays || video.currentTime > 0 ? fmt(_("%(clip)s paused at %(time)s of %(length)s s"), {clip: label, time: seconds(video.currentTime), length: seconds(video.duration || 0)}) : "";
      if (left !== null) { state += (state ? ". " : "") + fmt(_("%(left)s of %(limit)s plays left"), {left: left, limit: replayLimit}); }
      if (state !== announced) { count.textContent = announced = state; }
    }
    // A play from the start counts once; toggle knows it started one, for the "play" event
    // can come late on a busy machine, when the clip has already moved past its start.
    let fromStart = false;
    function toggle() {
      if (!video.paused && !video.ended) { video.pause(); return; }
      if (video.ended || video.currentTime === 0 || replayLimit !== null) { video.currentTime = 0; fromStart = true; }
      video.play().catch(function (error) { fromStart = false; log("error", clip, video.currentTime, {message: String(error)}); });
    }
    function seek(to) {
      if (replayLimit !== null || !isFinite(video.duration)) { return; }
      video.currentTime = Math.max(0, Math.min(video.duration, to));
      refresh();
    }
    button.addEventListener("click", toggle);
    video.addEventListener("click", function () { if (!button.disabled) { toggle(); } });
    button.addEventListener("keydown", function (event) {
      const moves = {ArrowLeft: -1, ArrowRight: 1};
      if (event.key in moves) { event.preventDefault(); seek(video.currentTime + moves[event.key]); }
      else if (event.key === "Home") { event.preventDefault(); video.pause(); seek(0); }
    });
    bar.addEventListener("click", function (event) {
      const box = bar.getBoundingClientRect();
      seek((event.clientX - box.left) / box.width * video.duration);
    });
    video.addEventListener("timeupdate", function () {
      fill.style.width = video.duration ? (100 * video.currentTime / video.duration) + "%" : "0";
    });
    video.addEventListener("play", function () {
      const started = fromStart || video.currentTime < 0.05;
      fromStart = false;
      if (started) {
        plays += 1;
        if (replayLimit !== null && plays > replayLimit) { video.pause(); plays -= 1; refresh(); return; }
      }
      log("play", clip, video.currentTime, {play: plays});
      refresh();
    });
    video.addEventListener("pause", function () { if (!video.ended) { log("pause", clip, video.currentTime); } refresh(); });
    video.addEventListener("seeked", function () { log("seek", clip, video.currentTime); });
    video.addEventListener("ended", function () {
      log("ended", clip, video.currentTime, {play: plays});
      watched.add(clip);
      updateFullView();
      refresh();
      flush();
    });
    video.addEventListener("error", function () {
      const code = video.error ? video.error.code : null;
      log("error", clip, null, {code: code});
      controls.append(Object.assign(document.createElement("p"), {className: "error", textContent: _("This clip could not be played. Please reload the page.")}));
    });
    refresh();
  });
  updateFullView();

  function show() {
    if (form.classList.contains("ready")) { return; }
    form.classList.add("ready");
    form.removeAttribute("aria-busy");
    shownAt = performance.now();
    log("page_shown", null, undefined, {width: window.innerWidth, height: window.innerHeight});
    flush();
  }
  const videos = figures.map(function (f) { return f.querySelector("video"); }).filter(Boolean);
  if (!videos.length) { show(); return; }
  form.setAttribute("aria-busy", "true");
  let loaded = 0;
  videos.forEach(function (video) {
    function one() { loaded += 1; if (loaded === videos.length) { show(); } }
    if (video.readyState >= 4) { one(); } else {
      video.addEventListener("canplaythrough", one, {once: true});
      video.addEventListener("error", one, {once: true});
    }
  });
  setTimeout(show, 10000);  // a slow connection: show what there is rather than nothing
})();
