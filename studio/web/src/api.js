// The one way the page talks to the studio: its JSON API, an answer's error becoming an Error.
export async function api(method, path, body, json = true) {
  const init = { method, headers: {} };
  if (body !== undefined) {
    init.body = json ? JSON.stringify(body) : body;
    init.headers["Content-Type"] = json ? "application/json" : "text/plain; charset=utf-8";
  }
  const res = await fetch(path, init);
  const data = await res.json().catch(() => ({}));
  if (!res.ok) throw new Error(data.error || `${method} ${path}: HTTP ${res.status}`);
  return data;
}
