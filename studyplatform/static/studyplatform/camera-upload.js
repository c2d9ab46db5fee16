/* Record a video with the webcam in an upload form and post it like a chosen file.
 *
 * A form with data-camera-field="NAME" gets its hidden "button.record" shown; the
 * recording is sent as the file field NAME (with data-camera-set="FIELD" that field is
 * sent as "on": a front camera's view is mirrored). The page reloads once it is saved;
 * the server's error is shown in ".record-status" otherwise. The script element's data
 * attributes carry its texts, translated by the page's template (data-record …). */
(function () {
  const texts = document.currentScript.dataset;
  if (!window.MediaRecorder || !navigator.mediaDevices) { return; }
  document.querySelectorAll("form[data-camera-field]").forEach(function (form) {
    const button = form.querySelector("button.record");
    const preview = form.querySelector("video.camera-preview");
    const status = form.querySelector(".record-status");
    let recorder = null;
    button.hidden = false;
    button.addEventListener("click", async function () {
      if (recorder && recorder.state === "recording") { recorder.stop(); return; }
      let stream;
      try { stream = await navigator.mediaDevices.getUserMedia({video: true, audio: false}); }
      catch (error) { status.textContent = texts.noCamera + " " + error.name; return; }
      const parts = [];
      preview.hidden = false; preview.srcObject = stream; preview.play().catch(function () {});
      recorder = new MediaRecorder(stream);
      recorder.ondataavailable = function (event) { if (event.data.size) { parts.push(event.data); } };
      recorder.onstop = async function () {
        stream.getTracks().forEach(function (track) { track.stop(); });
        preview.srcObject = null;
        button.textContent = texts.record;
        const data = new FormData(form);
        data.set(form.dataset.cameraField, new Blob(parts, {type: "video/webm"}), "camera.webm");
        if (form.dataset.cameraSet) { data.set(form.dataset.cameraSet, "on"); }
        status.textContent = texts.saving;
        const response = await fetch(location.href, {method: "POST", body: data, credentials: "same-origin",
                                                    headers: {"Accept": "application/json"}});
        const body = await response.json().catch(function () { return {}; });
        if (response.ok) { location.reload(); } else { status.textContent = body.error || texts.notSaved; }
      };
      recorder.start(500);
      button.textContent = texts.stop;
      status.textContent = texts.recording;
    });
  });
})();
