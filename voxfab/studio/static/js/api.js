// Talking to the studio server: JSON requests, job polling with progress, downloads.

export class ApiError extends Error {}

async function answer(resp) {
  const type = resp.headers.get('content-type') || '';
  if (!resp.ok) {
    let msg = `${resp.status} ${resp.statusText}`;
    if (type.includes('json')) msg = (await resp.json()).error || msg;
    else msg = (await resp.text()).trim() || msg;
    throw new ApiError(msg);
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

// Poll a job until it ends; onProgress(done, total, message) on each answer.
export async function waitJob(id, onProgress, intervalMs = 150) {
  for (;;) {
    const s = await get(`/api/jobs/${id}`);
    if (onProgress) onProgress(s.done, s.total, s.message);
    if (s.state === 'done') return s;
    if (s.state === 'error') throw new ApiError(s.message);
    await new Promise((r) => setTimeout(r, intervalMs));
  }
}

// Save a blob under a name through a temporary link (the browser's download).
export function saveBlob(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url; a.download = name; document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

export function fileUrl(job, index) { return `/api/files/${job}/${index}`; }
