// The page's wasm arrives packed with xz (web/build/pack-wasm.mjs writes NAME.xz beside
// NAME): about a quarter fewer bytes than the gzip a host such as GitHub Pages sends, on
// every host, since the page unpacks it itself. The build bundles this module with the
// decoder (xzwasm: xz-embedded compiled to wasm, a 9 kB download); index.html's loader and
// the lazy module's glue start their wasm with `startPacked`, and the app's init compiles
// the unpacked bytes while they arrive.
import { XzReadableStream } from 'xzwasm';

/**
 * The wasm at `url`, as a Response for WebAssembly.instantiateStreaming, unpacked from
 * `url + '.xz'` as it downloads. Rejects where that copy cannot be fetched; a copy that
 * fails while it unpacks errors the Response's body, and so the init that reads it.
 */
export default async function packedWasm(url) {
  const packed = await fetch(url + '.xz');
  if (!packed.ok || !packed.body) throw new Error(`${url}.xz: ${packed.status}`);
  const body = copied(new XzReadableStream(packed.body));
  return new Response(body, { headers: { 'content-type': 'application/wasm' } });
}

/**
 * Starts a wasm-bindgen module, `init` its init function, from its wasm at `url`: from the
 * packed copy, or, where that copy is missing or fails partway, from `url` itself (a
 * failed init may be called again).
 */
export async function startPacked(init, url) {
  try {
    return await init({ module_or_path: packedWasm(url) });
  } catch {
    return init({ module_or_path: url });
  }
}

/**
 * `stream`'s chunks, each copied the moment it is read. The decoder's chunks are views of
 * one output buffer in its memory, which its next step writes over: a chunk left waiting in
 * its queue would be overwritten before anyone read it (Response.arrayBuffer over the
 * decoder alone returns wrong bytes). So a read is always waiting here: the decoder hands
 * each chunk straight to it, the copy is made before the decoder's next step (which the
 * streams' rules run after the reader's reaction), and the next read is asked at once.
 */
function copied(stream) {
  const reader = stream.getReader();
  return new ReadableStream({
    async start(controller) {
      try {
        for (let read = await reader.read(); !read.done; read = await reader.read()) {
          controller.enqueue(read.value.slice());
        }
        controller.close();
      } catch (e) {
        controller.error(e);
      } finally {
        // The decoder keeps its wasm instance, with the dictionary's few MB of memory, for
        // another stream; the page unpacks one.
        XzReadableStream._moduleInstance = XzReadableStream._moduleInstancePromise = undefined;
      }
    },
  });
}
