// Talking to the studio server: JSON requests, job polling with progress, downloads.

// An error the server explained: `message` in the artist's words, `detail` the technical line (a tooltip).
export class ApiError extends Error {
  constructor(message, detail = '') { super(message); this.detail = detail || ''; }
}

async function answer(resp) {
  const type = resp.headers.get('content-type') || '';
  if (!resp.ok) {
    let msg = `${resp.status} ${resp.statusText}`, detail = '';
    if (type.includes('json')) { const j = await resp.json(); msg = j.error || msg; detail = j.detail || ''; }
    else msg = (await resp.text()).trim() || msg;
    throw new ApiError(msg, detail);
  }
  return type.includes('json') ? resp.json() : resp.blob();
}

export async function post(url, body) {
  const resp = await fetch(url, {
    method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(body),
  });
  return answer(resp);
}

export async function get(url) {
  return answer(await fetch(url));
}

// The jobs being waited for now (what the Cancel button stops).
const waiting = new Set();
export function waitingJobs() { return [...waiting]; }

export class Cancelled extends ApiError {}

function ordinal(n) { return n === 1 ? '1st' : n === 2 ? '2nd' : n === 3 ? '3rd' : `${n}th`; }

// What a job is doing, in words: its place in the queue, or its own progress message.
export function jobText(s) {
  if (s.state === 'queued') return `waiting: ${ordinal(s.place)} in the queue`;
  if (s.state === 'cancelled') return 'cancelled';
  return s.message || 'working';
}

// Ask the server to stop a job (it stops within about a second).
export function cancelJob(id) { return post(`/api/jobs/${id}/cancel`, {}); }

// Poll a job until it ends; onProgress(done, total, text, status) on each answer, and
// onItems(items, from) with the items it made since the last answer (a gallery's nets, as each is made).
// Throws ApiError when it failed, Cancelled when it was cancelled.
export async function waitJob(id, onProgress, intervalMs = 150, onItems = null) {
  waiting.add(id);
  let read = 0;
  try {
    for (;;) {
      const s = await get(onItems ? `/api/jobs/${id}?since=${read}` : `/api/jobs/${id}`);
      if (onItems && s.items && s.items.length) { onItems(s.items, read); read += s.items.length; }
      if (onProgress) onProgress(s.done, s.total, jobText(s), s);
      if (s.state === 'done') return s;
      if (s.state === 'error') throw new ApiError(s.message, s.detail);
      if (s.state === 'cancelled') throw new Cancelled('Cancelled.');
      await new Promise((r) => setTimeout(r, intervalMs));
    }
  } finally { waiting.delete(id); }
}

// Save a blob under a name through a temporary link (the browser's download).
export function saveBlob(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url; a.download = name; document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

export function fileUrl(job, index) { return `/api/files/${job}/${index}`; }
