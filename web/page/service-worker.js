// ArmLab's service worker: after one visit the page opens with no network (a lecture hall
// whose Wi-Fi fails). The build writes it into dist/ (web/build/service-worker-build.mjs, a trunk
// post_build hook) with one line before this text: ARMLAB_BUILD = {version, files}, the
// build's own files and a hash of their contents. Registered by index.html.
//
// What the page needs is those files: index.html, the JS glue, the wasm packed with xz and
// its decoder (the page unpacks it on every visit; the wasm itself, its fallback, is not in
// the list), the manifest and the icon. The fonts are compiled into the wasm (include_bytes!
// in src/app/widgets/style.rs), so caching the wasm caches the fonts. The one file the app
// fetches at run time, the URDF module (urdf/, on the first URDF file opened or saved), is
// in the build's list too.
//
// - install: puts this build's files into the cache named by its version.
// - activate: deletes every other ArmLab cache of this scope, and takes over open pages.
// - fetch: same-origin GETs come from the cache first, else from the network. The page
//   itself (index.html, whatever the query) is asked from the network first, with the
//   cached copy as the answer when the network fails or is slower than PAGE_TIMEOUT_MS:
//   index.html is the one file without a hash in its name and it names the build's hashed
//   JS and wasm, so online every load runs the newest build (a developer rebuilding with
//   `trunk serve` is never held on an old one; the new build's files are not in the old
//   cache and come from the network), and offline the page opens from the cache.
// A new build has a new version: its worker installs beside the old one, replaces it at
// once (skipWaiting), and its activation deletes the old cache.
/* global ARMLAB_BUILD */
'use strict';

const SCOPE = self.registration.scope;
// Caches are shared by the whole origin (a university web space holds many people's
// folders): the scope in the name keeps two copies of ArmLab from deleting each other's.
const PREFIX = `armlab ${SCOPE} `;
const CACHE = PREFIX + ARMLAB_BUILD.version;
// The build's files sit beside this worker.
const INDEX = new URL('index.html', self.location);
// The page's two addresses; a navigation's query and hash do not matter.
const PAGE_PATHS = [new URL(SCOPE).pathname, INDEX.pathname];
const PAGE_TIMEOUT_MS = 3000;

self.addEventListener('install', (event) => {
  event.waitUntil((async () => {
    const cache = await caches.open(CACHE);
    // 'no-cache' revalidates with the server: an index.html from the HTTP cache (an older
    // build's, naming files this build does not have) must not enter this build's cache.
    await cache.addAll(ARMLAB_BUILD.files.map((file) => new Request(new URL(file, self.location).href, { cache: 'no-cache' })));
    await self.skipWaiting();
  })());
});

self.addEventListener('activate', (event) => {
  event.waitUntil((async () => {
    const old = (await caches.keys()).filter((name) => name.startsWith(PREFIX) && name !== CACHE);
    await Promise.all(old.map((name) => caches.delete(name)));
    await self.clients.claim();
  })());
});

self.addEventListener('fetch', (event) => {
  const request = event.request;
  const url = new URL(request.url);
  if (request.method !== 'GET' || url.origin !== self.location.origin) return;
  const isPage = request.mode === 'navigate' && PAGE_PATHS.includes(url.pathname);
  event.respondWith(isPage ? page(request) : cacheFirst(request));
});

async function cacheFirst(request) {
  const cached = await (await caches.open(CACHE)).match(request);
  return cached ?? fetch(request);
}

async function page(request) {
  const cached = await (await caches.open(CACHE)).match(INDEX.href);
  if (!cached) return fetch(request);
  let timer;
  const late = new Promise((resolve) => { timer = setTimeout(() => resolve(cached), PAGE_TIMEOUT_MS); });
  // A server error (the web space is down) also gets the cached page; a redirect or a
  // missing page is the server's answer to give.
  const network = fetch(request).then((response) => (response.status >= 500 ? cached : response), () => cached);
  try {
    return await Promise.race([network, late]);
  } finally {
    clearTimeout(timer);
  }
}
