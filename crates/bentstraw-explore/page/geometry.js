// Vectors, and the eye's orbit round the glass (azimuth, elevation, distance).

// The centre the eye orbits round: the middle of the glass.
export const ORBIT = [0, 0, 0.1];

export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const scale = (a, k) => [a[0] * k, a[1] * k, a[2] * k];

/** The observer's azimuth and elevation (degrees) and distance round the orbit centre. */
export function orbitOf(o) {
  const d = sub(o, ORBIT), r = Math.hypot(d[0], d[1]);
  return { az: Math.atan2(d[1], d[0]) * 180 / Math.PI, el: Math.atan2(d[2], r) * 180 / Math.PI, dist: Math.hypot(r, d[2]) };
}
export function fromOrbit(az, el, dist) {
  const a = az * Math.PI / 180, e = el * Math.PI / 180;
  return add(ORBIT, [dist * Math.cos(e) * Math.cos(a), dist * Math.cos(e) * Math.sin(a), dist * Math.sin(e)]);
}
