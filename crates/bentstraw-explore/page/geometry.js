// Vectors, the eye's orbit round the glass (azimuth, elevation, distance), and a glass of
// revolution's profiles.

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

/** The radius of a profile (`[r, z]` points, `z` rising) at the height `z`, straight between its
 * points: the wall is smooth through them and its radius stays between theirs, so this is near
 * it everywhere and exact for a straight wall; null off the profile's heights. */
export function profileAt(profile, z) {
  for (let i = 1; i < profile.length; i++) {
    const [r0, z0] = profile[i - 1], [r1, z1] = profile[i];
    if (z >= z0 && z <= z1) return r0 + ((r1 - r0) * (z - z0)) / (z1 - z0);
  }
  return null;
}
/** The greatest radius of a profile: its widest point's (between two points the wall's radius
 * stays between theirs). */
export const widest = (profile) => Math.max(...profile.map((q) => q[0]));
