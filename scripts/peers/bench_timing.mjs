// scripts/peers/bench_timing.mjs: what both peer pages of scripts/peers/bench_peer.mjs share (it
// serves this file as /bench_timing.mjs): the timed frames and the picture handed back.

function quantile(sorted, q) {
    const i = (sorted.length - 1) * q, lo = Math.floor(i), hi = Math.ceil(i);
    return sorted[lo] + (sorted[hi] - sorted[lo]) * (i - lo);
}

// `warmup` untimed calls of frame(), then `frames` timed ones: their quartiles and minimum (ms).
export function timeFrames(frame, warmup, frames) {
    for (let i = 0; i < warmup; i++) frame();
    const times = [];
    for (let i = 0; i < frames; i++) {
        const t0 = performance.now();
        frame();
        times.push(performance.now() - t0);
    }
    const sorted = times.slice().sort((a, b) => a - b);
    return { median_ms: quantile(sorted, 0.5), q1_ms: quantile(sorted, 0.25), q3_ms: quantile(sorted, 0.75),
        min_ms: sorted[0], frames: times.length };
}

// Bytes as base64, in chunks that String.fromCharCode's argument count takes.
export function toBase64(bytes) {
    let s = '';
    for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return btoa(s);
}
