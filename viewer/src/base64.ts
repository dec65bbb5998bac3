// Base64 <-> bytes. The report's arrays are little-endian raw bytes in base64 (a tenth of the size
// of JSON numbers and exact). The decoder prefers the browser's native Uint8Array.fromBase64 (fast
// on the 10+ MB of a long run) and falls back to atob, which node and every browser have.

type FromBase64 = (s: string) => Uint8Array;

export class Base64Error extends Error {}

export function base64ToBytes(s: string): Uint8Array {
  const native = (Uint8Array as unknown as { fromBase64?: FromBase64 }).fromBase64;
  try {
    if (typeof native === 'function') return native.call(Uint8Array, s);
    const bin = atob(s);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out;
  } catch (e) {
    throw new Base64Error(`not valid base64 (${(e as Error).message})`);
  }
}

/** Used by tests and tools that build reports; chunked so String.fromCharCode gets few arguments. */
export function bytesToBase64(bytes: Uint8Array): string {
  let bin = '';
  const CHUNK = 0x8000;
  for (let i = 0; i < bytes.length; i += CHUNK) {
    bin += String.fromCharCode(...bytes.subarray(i, i + CHUNK));
  }
  return btoa(bin);
}
