//! The single-precision packet tracer for course-mode pictures: eight rays at a time, structure of
//! arrays, branch-free, so that the compiler maps each step onto one 8-wide SIMD instruction.
//!
//! The physics is SPEC §3 exactly as in [`crate::tracer`], with the same rules for which face a
//! ray can meet next (the face it has just left is excluded exactly, the opaque straw counts only
//! where a ray enters it); only the arithmetic differs (f32, good to ~1e-8 m at the scale of the
//! glass). A pixel's colour can therefore differ from the double-precision tracer's only where the
//! answer changes within a hair of the ray: on the picture's colour boundaries. The tests bound
//! how many pixels differ and check that they all lie on boundaries. Image points never use this
//! path; they stay in double precision.
//!
//! An eye farther than [`FAR_EYE`] from the scene cannot be written in f32 to the precision the
//! glass needs (at 1 km an f32 is good to 6e-5 m): each ray is then made in double precision and
//! brought to the scene's bounding sphere ([`enter_bounding_sphere`]) before it is rounded to f32,
//! so a far view is as sharp as a near one.
//!
//! The same generic code is compiled twice: for AVX2 (chosen at run time with
//! `is_x86_feature_detected!`) and for the baseline target. Both use the same IEEE operations in the
//! same order (no fused multiply-add), so both give the same pixels.

use crate::camera::Camera;
use crate::geometry::{enter_bounding_sphere, Ray, BOUNDING_CENTRE};
use crate::scene::{
    Scene, GLASS_RADIUS, SECTION_COUNT, SECTION_HEIGHT, STRAW_HEIGHT, STRAW_RADIUS,
};
use crate::trace::FRESNEL_SEGMENTS_PER_RAY;
use crate::Vec3;

/// Rays per packet.
pub const LANES: usize = 8;

/// Distance (m) from the scene's centre beyond which an eye's rays are made in double precision
/// and started on the scene's bounding sphere.
pub const FAR_EYE: f64 = 1.0;

/// Code of "no face" in a lane's record of the face it has just left (0 side, 1 top, 2 bottom).
const NO_FACE: f32 = -1.0;

/// Eight `f32`s, one per ray.
#[derive(Clone, Copy, Debug)]
struct F8([f32; LANES]);

/// Eight lane masks (all bits set = true).
#[derive(Clone, Copy, Debug)]
struct M8([u32; LANES]);

macro_rules! lanewise {
    ($trait:ident, $method:ident, $op:tt) => {
        impl std::ops::$trait for F8 {
            type Output = F8;
            #[inline(always)]
            fn $method(self, o: F8) -> F8 {
                F8(std::array::from_fn(|k| self.0[k] $op o.0[k]))
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl std::ops::Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        self.map(|x| -x)
    }
}

macro_rules! compare {
    ($name:ident, $op:tt) => {
        #[inline(always)]
        fn $name(self, o: F8) -> M8 {
            M8(std::array::from_fn(|k| if self.0[k] $op o.0[k] { u32::MAX } else { 0 }))
        }
    };
}

impl F8 {
    #[inline(always)]
    fn splat(x: f32) -> F8 {
        F8([x; LANES])
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> F8 {
        F8(std::array::from_fn(|k| f(self.0[k])))
    }
    #[inline(always)]
    fn sqrt(self) -> F8 {
        self.map(f32::sqrt)
    }
    #[inline(always)]
    fn max(self, o: F8) -> F8 {
        F8(std::array::from_fn(|k| {
            if self.0[k] > o.0[k] {
                self.0[k]
            } else {
                o.0[k]
            }
        }))
    }
    #[inline(always)]
    fn abs(self) -> F8 {
        self.map(f32::abs)
    }
    compare!(lt, <);
    compare!(eq, ==);
    compare!(le, <=);
    compare!(gt, >);
    compare!(ge, >=);
}

impl M8 {
    #[inline(always)]
    fn splat(b: bool) -> M8 {
        M8([if b { u32::MAX } else { 0 }; LANES])
    }
    #[inline(always)]
    fn and(self, o: M8) -> M8 {
        M8(std::array::from_fn(|k| self.0[k] & o.0[k]))
    }
    #[inline(always)]
    fn or(self, o: M8) -> M8 {
        M8(std::array::from_fn(|k| self.0[k] | o.0[k]))
    }
    #[inline(always)]
    fn and_not(self, o: M8) -> M8 {
        M8(std::array::from_fn(|k| self.0[k] & !o.0[k]))
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().fold(0, |a, &b| a | b) != 0
    }
    /// `a` where the mask is set, else `b`.
    #[inline(always)]
    fn select(self, a: F8, b: F8) -> F8 {
        F8(std::array::from_fn(|k| {
            f32::from_bits((a.0[k].to_bits() & self.0[k]) | (b.0[k].to_bits() & !self.0[k]))
        }))
    }
}

/// The scene in single precision, ready for packets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PacketTracer {
    straw_x: f32,
    straw_y: f32,
    water_height: f32,
    has_water: bool,
    /// `n1/n2` from air into water, and from water into air.
    eta_into_water: f32,
    eta_into_air: f32,
    max_events: u32,
}

impl PacketTracer {
    /// Prepares `scene` for single-precision packets.
    pub fn new(scene: &Scene) -> PacketTracer {
        PacketTracer {
            straw_x: scene.straw_x as f32,
            straw_y: scene.straw_y as f32,
            water_height: scene.water_height as f32,
            has_water: scene.has_water(),
            eta_into_water: (1.0 / scene.n_water) as f32,
            eta_into_air: scene.n_water as f32,
            max_events: scene.max_events,
        }
    }

    /// Colour codes (0 = none) of the rays through the centres of pixel row `row` of `camera`;
    /// `codes.len()` must be the camera's width.
    pub fn course_row(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2, checked just above.
                unsafe { self.course_row_avx2(camera, row, codes) };
                return;
            }
        }
        self.course_row_generic(camera, row, codes);
    }

    /// [`Self::course_row`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn course_row_avx2(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        self.course_row_generic(camera, row, codes);
    }

    /// [`Self::course_row`] for any target (the baseline instruction set).
    pub fn course_row_portable(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        self.course_row_generic(camera, row, codes);
    }

    #[inline(always)]
    fn course_row_generic(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        let rays = row_rays(camera, row);
        for (p, chunk) in codes.chunks_mut(LANES).enumerate() {
            let (o, d, alive) = rays(p);
            let out = self.trace8(o, d, alive);
            for (c, o) in chunk.iter_mut().zip(out) {
                *c = o;
            }
        }
    }

    /// Fresnel weights per section (SPEC §6) of the rays through the centres of pixel row `row`;
    /// `weights.len()` must be the camera's width. `wave` holds reusable buffers.
    ///
    /// Traced breadth first: every branch alive after `k` events is in one list, traced eight at a
    /// time; the list of their children is the next. So lanes stay full whatever the tree's shape.
    /// Branches lighter than `prune_below` are abandoned, branches that provably escape (out
    /// of the water through the side or bottom, or mirrored off their outside) are not followed,
    /// and at most [`FRESNEL_SEGMENTS_PER_RAY`] segments are followed per pixel.
    pub fn fresnel_row(
        &self,
        camera: &Camera,
        row: u32,
        prune_below: f64,
        wave: &mut FresnelWave,
        weights: &mut [[f64; SECTION_COUNT]],
    ) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2, checked just above.
                unsafe { self.fresnel_row_avx2(camera, row, prune_below, wave, weights) };
                return;
            }
        }
        self.fresnel_row_generic(camera, row, prune_below, wave, weights);
    }

    /// [`Self::fresnel_row`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn fresnel_row_avx2(
        &self,
        camera: &Camera,
        row: u32,
        prune_below: f64,
        wave: &mut FresnelWave,
        weights: &mut [[f64; SECTION_COUNT]],
    ) {
        self.fresnel_row_generic(camera, row, prune_below, wave, weights);
    }

    /// [`Self::fresnel_row`] for any target (the baseline instruction set).
    pub fn fresnel_row_portable(
        &self,
        camera: &Camera,
        row: u32,
        prune_below: f64,
        wave: &mut FresnelWave,
        weights: &mut [[f64; SECTION_COUNT]],
    ) {
        self.fresnel_row_generic(camera, row, prune_below, wave, weights);
    }

    #[inline(always)]
    fn fresnel_row_generic(
        &self,
        camera: &Camera,
        row: u32,
        prune_below: f64,
        wave: &mut FresnelWave,
        weights: &mut [[f64; SECTION_COUNT]],
    ) {
        debug_assert_eq!(weights.len(), camera.width as usize);
        for w in weights.iter_mut() {
            *w = [0.0; SECTION_COUNT];
        }
        // The picture's breadth-first loop, keeping only the weight that reaches the straw.
        self.branch_ends_row_generic(camera, row, true, prune_below, wave, &mut |pixel, end| {
            if let BranchEnd::Straw { code, weight, .. } = end {
                weights[pixel][code as usize - 1] += weight as f64;
            }
        });
    }

    /// How every branch of the rays through the centres of pixel row `row` ends, for a picture
    /// that shows what each branch meets: `on_end(pixel, end)` once per branch end.
    ///
    /// With `split` (SPEC §6, fresnel) each branch splits at every water face by the Fresnel
    /// reflectance, branches lighter than `prune_below` are abandoned; without it (SPEC §3, course)
    /// each ray is refracted or totally reflected and keeps weight 1. Branches that provably
    /// escape (out of the water through the side or bottom, or mirrored off their outside) are
    /// reported as escaping from the face at once. Traced breadth first, so the lanes stay full
    /// (see [`Self::fresnel_row`], which is this loop keeping only the straw's weights).
    pub fn branch_ends_row(
        &self,
        camera: &Camera,
        row: u32,
        split: bool,
        prune_below: f64,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2, checked just above.
                unsafe { self.branch_ends_row_avx2(camera, row, split, prune_below, wave, on_end) };
                return;
            }
        }
        self.branch_ends_row_generic(camera, row, split, prune_below, wave, on_end);
    }

    /// [`Self::branch_ends_row`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn branch_ends_row_avx2(
        &self,
        camera: &Camera,
        row: u32,
        split: bool,
        prune_below: f64,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        self.branch_ends_row_generic(camera, row, split, prune_below, wave, on_end);
    }

    #[inline(always)]
    fn branch_ends_row_generic(
        &self,
        camera: &Camera,
        row: u32,
        split: bool,
        prune_below: f64,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        let width = camera.width as usize;
        let eye = [
            camera.eye.x as f32,
            camera.eye.y as f32,
            camera.eye.z as f32,
        ];
        wave.eye = eye;
        let cur = &mut wave.current;
        cur.clear();
        cur.reserve_total(width);
        let rays = row_rays(camera, row);
        for (p, chunk_start) in (0..width).step_by(LANES).enumerate() {
            let ([ox, oy, oz], [dx, dy, dz], alive) = rays(p);
            for k in 0..LANES.min(width - chunk_start) {
                let direction = [dx.0[k], dy.0[k], dz.0[k]];
                if alive.0[k] == 0 {
                    // Misses the scene: straight on to the backdrop.
                    on_end(
                        chunk_start + k,
                        BranchEnd::Escaped {
                            origin: eye,
                            direction,
                            weight: 1.0,
                        },
                    );
                    continue;
                }
                cur.push(
                    [ox.0[k], oy.0[k], oz.0[k]],
                    direction,
                    1.0,
                    false,
                    (chunk_start + k) as u32,
                    NO_FACE,
                );
            }
        }
        self.follow_branches(
            split,
            prune_below,
            FRESNEL_SEGMENTS_PER_RAY,
            width,
            wave,
            on_end,
        );
    }

    /// [`Self::branch_ends_row`] for any rays from `eye` along unit `directions`, each following
    /// at most `max_segments` segments; `on_end` is given the index of the ray in `directions`.
    #[allow(clippy::too_many_arguments)]
    pub fn branch_ends(
        &self,
        eye: Vec3,
        directions: &[Vec3],
        split: bool,
        prune_below: f64,
        max_segments: u32,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2, checked just above.
                unsafe {
                    self.branch_ends_avx2(
                        eye,
                        directions,
                        split,
                        prune_below,
                        max_segments,
                        wave,
                        on_end,
                    )
                };
                return;
            }
        }
        self.branch_ends_generic(
            eye,
            directions,
            split,
            prune_below,
            max_segments,
            wave,
            on_end,
        );
    }

    /// [`Self::branch_ends`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn branch_ends_avx2(
        &self,
        eye: Vec3,
        directions: &[Vec3],
        split: bool,
        prune_below: f64,
        max_segments: u32,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        self.branch_ends_generic(
            eye,
            directions,
            split,
            prune_below,
            max_segments,
            wave,
            on_end,
        );
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn branch_ends_generic(
        &self,
        eye: Vec3,
        directions: &[Vec3],
        split: bool,
        prune_below: f64,
        max_segments: u32,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        let v = |x: Vec3| [x.x as f32, x.y as f32, x.z as f32];
        let far = (eye - BOUNDING_CENTRE).length() > FAR_EYE;
        wave.eye = v(eye);
        let cur = &mut wave.current;
        cur.clear();
        cur.reserve_total(directions.len());
        for (k, &d) in directions.iter().enumerate() {
            // A far eye's rays start on the bounding sphere, made in double precision.
            let start = if far {
                enter_bounding_sphere(Ray {
                    origin: eye,
                    direction: d,
                })
                .map(|(r, _)| r.origin)
            } else {
                Some(eye)
            };
            match start {
                Some(o) => cur.push(v(o), v(d), 1.0, false, k as u32, NO_FACE),
                None => on_end(
                    k,
                    BranchEnd::Escaped {
                        origin: v(eye),
                        direction: v(d),
                        weight: 1.0,
                    },
                ),
            }
        }
        self.follow_branches(
            split,
            prune_below,
            max_segments,
            directions.len(),
            wave,
            on_end,
        );
    }

    /// Follows the branches in `wave.current` to their ends, breadth first (see
    /// [`Self::branch_ends_row`]), at most `max_segments` segments for each of the `pixels`
    /// pixels (what still travels then is dropped).
    #[inline(always)]
    fn follow_branches<E: FnMut(usize, BranchEnd)>(
        &self,
        split: bool,
        prune_below: f64,
        max_segments: u32,
        pixels: usize,
        wave: &mut FresnelWave,
        on_end: &mut E,
    ) {
        let prune = prune_below as f32;
        let n_water = self.eta_into_air;
        let eye = wave.eye;
        let segments = &mut wave.segments;
        segments.clear();
        segments.resize(pixels, 1);
        let (cur, next) = (&mut wave.current, &mut wave.next);
        let lane = |v: &[F8; 3], k: usize| [v[0].0[k], v[1].0[k], v[2].0[k]];
        for event in 0..=self.max_events {
            if cur.len() == 0 {
                break;
            }
            next.clear();
            next.reserve_total(2 * cur.len());
            for base in (0..cur.len()).step_by(LANES) {
                let n = LANES.min(cur.len() - base);
                let alive = M8(std::array::from_fn(|k| if k < n { u32::MAX } else { 0 }));
                let o = [cur.load(0, base), cur.load(1, base), cur.load(2, base)];
                let d = [cur.load(3, base), cur.load(4, base), cur.load(5, base)];
                let left = cur.load_left(base);
                let escape = |k: usize, on_end: &mut E| {
                    // A branch that met nothing is the ray from the eye (a far eye's rays start
                    // on the bounding sphere, possibly past the backdrop's floor).
                    let origin = if cur.left[base + k] == NO_FACE {
                        eye
                    } else {
                        lane(&o, k)
                    };
                    on_end(
                        cur.pixel[base + k] as usize,
                        BranchEnd::Escaped {
                            origin,
                            direction: lane(&d, k),
                            weight: cur.w[base + k],
                        },
                    )
                };
                let Some(hit) = self.hit8(o, d, alive, left) else {
                    for k in 0..n {
                        escape(k, on_end);
                    }
                    continue;
                };
                let inf = F8::splat(f32::INFINITY);
                let hits_straw = alive
                    .and(hit.t_straw.lt(inf))
                    .and(hit.t_straw.le(hit.t_water));
                let hits_water = alive.and_not(hits_straw).and(hit.t_water.lt(inf));
                for k in 0..n {
                    let pixel = cur.pixel[base + k] as usize;
                    let w = cur.w[base + k];
                    if hits_straw.0[k] != 0 {
                        let t = hit.t_straw.0[k];
                        let [ox, oy, oz] = lane(&o, k);
                        let [dx, dy, dz] = lane(&d, k);
                        on_end(
                            pixel,
                            BranchEnd::Straw {
                                code: hit.straw_code.0[k] as u8,
                                point: [ox + t * dx, oy + t * dy, oz + t * dz],
                                weight: w,
                            },
                        );
                    } else if hits_water.0[k] == 0 {
                        escape(k, on_end);
                    } else if event == self.max_events {
                        on_end(pixel, BranchEnd::Dropped { weight: w });
                    }
                }
                if event == self.max_events || !hits_water.any() {
                    continue;
                }
                let in_water = M8(std::array::from_fn(|k| {
                    if k < n && cur.in_water[base + k] {
                        u32::MAX
                    } else {
                        0
                    }
                }));
                let b = self.bend8(o, d, hit.t_water, hit.water_face, in_water);
                let one = F8::splat(1.0);
                let nw = F8::splat(n_water);
                let (n1, n2) = (in_water.select(nw, one), in_water.select(one, nw));
                let rs = (n1 * b.cos_i - n2 * b.cos_t) / (n1 * b.cos_i + n2 * b.cos_t);
                let rp = (n2 * b.cos_i - n1 * b.cos_t) / (n2 * b.cos_i + n1 * b.cos_t);
                let r = b.total.select(one, F8::splat(0.5) * (rs * rs + rp * rp));
                for k in 0..n {
                    if hits_water.0[k] == 0 {
                        continue;
                    }
                    let (w, water, pixel) =
                        (cur.w[base + k], cur.in_water[base + k], cur.pixel[base + k]);
                    let total = b.total.0[k] != 0;
                    // Course: the one branch the law picks keeps the whole weight.
                    let (wr, wt) = match (split, total) {
                        (_, true) => (w, 0.0),
                        (true, false) => (w * r.0[k], w - w * r.0[k]),
                        (false, false) => (0.0, w),
                    };
                    let q = lane(&b.q, k);
                    // Out through the side or bottom, or mirrored off their outside: escapes.
                    let (reflected_escapes, refracted_escapes) = if b.is_top.0[k] == 0 {
                        (!water, water)
                    } else {
                        (false, false)
                    };
                    let face = hit.water_face.0[k];
                    for (weight, directions, escapes, to_water) in [
                        (wr, &b.reflected, reflected_escapes, water),
                        (wt, &b.refracted, refracted_escapes, !water),
                    ] {
                        if weight <= 0.0 || (split && weight < prune) {
                            continue;
                        }
                        let dir = lane(directions, k);
                        let used = &mut segments[pixel as usize];
                        if !escapes && *used >= max_segments {
                            // The pixel's work is spent: dropped, like light past the limit.
                            on_end(pixel as usize, BranchEnd::Dropped { weight });
                            continue;
                        }
                        if escapes {
                            on_end(
                                pixel as usize,
                                BranchEnd::Escaped {
                                    origin: q,
                                    direction: dir,
                                    weight,
                                },
                            );
                        } else {
                            *used += 1;
                            next.push(q, dir, weight, to_water, pixel, face);
                        }
                    }
                }
            }
            std::mem::swap(cur, next);
        }
    }

    /// Colour codes of eight rays from `o` along unit directions `d` (lanes not `alive` see
    /// nothing).
    #[inline(always)]
    fn trace8(&self, o: [F8; 3], d: [F8; 3], alive: M8) -> [u8; LANES] {
        let inf = F8::splat(f32::INFINITY);
        let zero = F8::splat(0.0);

        let [mut ox, mut oy, mut oz] = o;
        let [mut dx, mut dy, mut dz] = d;
        let mut alive = alive;
        let mut in_water = M8::splat(false);
        let mut left = F8::splat(NO_FACE);
        // Colour codes as floats, 0 = none.
        let mut code = zero;

        for event in 0..=self.max_events {
            if !alive.any() {
                break;
            }
            let Some(hit) = self.hit8([ox, oy, oz], [dx, dy, dz], alive, left) else {
                break;
            };
            let Hit8 {
                t_water,
                water_face,
                t_straw,
                straw_code,
            } = hit;

            // What each live ray does now.
            let hits_straw = alive.and(t_straw.lt(inf)).and(t_straw.le(t_water));
            code = hits_straw.select(straw_code, code);
            let hits_water = alive.and_not(hits_straw).and(t_water.lt(inf));
            alive = if event == self.max_events {
                M8::splat(false) // an (event+1)-th event would be needed: dropped
            } else {
                hits_water
            };
            if !alive.any() {
                break;
            }

            // Refraction or total reflection at the water face, for the live rays.
            let bend = self.bend8([ox, oy, oz], [dx, dy, dz], t_water, water_face, in_water);
            let Bend8 {
                q,
                refracted,
                reflected,
                total,
                is_top,
                ..
            } = bend;
            let [qx, qy, qz] = q;
            let [rx, ry, rz] = refracted;
            let [lx, ly, lz] = reflected;
            dx = alive.select(total.select(lx, rx), dx);
            dy = alive.select(total.select(ly, ry), dy);
            dz = alive.select(total.select(lz, rz), dz);
            ox = alive.select(qx, ox);
            oy = alive.select(qy, oy);
            oz = alive.select(qz, oz);
            left = alive.select(water_face, left);
            let crossed = alive.and_not(total);
            // A ray leaving the water through the side wall moves away from the axis for good, and
            // one leaving through the bottom moves down for good: neither can meet any face again
            // (all lie inside the glass's circle, above z = 0). Only a ray out through the top
            // may still meet the straw.
            let out_not_top = crossed.and(in_water).and_not(is_top);
            alive = alive.and_not(out_not_top);
            in_water = M8(std::array::from_fn(|k| in_water.0[k] ^ crossed.0[k]));
        }
        std::array::from_fn(|k| code.0[k] as u8)
    }

    /// The nearest water face and straw face ahead of eight rays (infinite distances for none),
    /// each lane having just left water face `left` (0 side, 1 top, 2 bottom, [`NO_FACE`]);
    /// `None` when no live ray's line comes near the glass at all.
    #[inline(always)]
    fn hit8(&self, o: [F8; 3], d: [F8; 3], alive: M8, left: F8) -> Option<Hit8> {
        let inf = F8::splat(f32::INFINITY);
        let zero = F8::splat(0.0);
        let rv2 = F8::splat((GLASS_RADIUS * GLASS_RADIUS) as f32);
        let rp2 = F8::splat((STRAW_RADIUS * STRAW_RADIUS) as f32);
        let he = F8::splat(self.water_height);
        let hp = F8::splat(STRAW_HEIGHT as f32);
        let (sx, sy) = (F8::splat(self.straw_x), F8::splat(self.straw_y));
        let water_on = M8::splat(self.has_water);
        let [ox, oy, oz] = o;
        let [dx, dy, dz] = d;
        let a = dx * dx + dy * dy;
        let inv_a = F8::splat(1.0) / a;
        let inv_dz = F8::splat(1.0) / dz;
        let left_side = left.eq(F8::splat(0.0));
        let left_top = left.eq(F8::splat(1.0));
        let left_bottom = left.eq(F8::splat(2.0));

        // Water side wall: the first root ahead with 0 <= z <= he; for a ray that has just left
        // it (it starts on it), the root away from its start.
        let b = ox * dx + oy * dy;
        let c = ox * ox + oy * oy - rv2;
        let disc = b * b - a * c;
        if !alive.and(disc.ge(zero)).any() {
            return None; // every live ray's line misses the glass, which holds every face
        }
        let sq = disc.max(zero).sqrt();
        let t0 = (-b - sq) * inv_a;
        let t1 = (-b + sq) * inv_a;
        let z0 = oz + t0 * dz;
        let z1 = oz + t1 * dz;
        let ok0 = t0.gt(zero).and(z0.ge(zero)).and(z0.le(he));
        let ok1 = t1.gt(zero).and(z1.ge(zero)).and(z1.le(he));
        let real = disc.ge(zero);
        let t_side = ok0.select(t0, ok1.select(t1, inf));
        let start_is_t0 = t0.abs().lt(t1.abs());
        let t_again = start_is_t0.select(t1, t0);
        let ok_again = start_is_t0.and(ok1).or(ok0.and_not(start_is_t0));
        let t_side = left_side.select(ok_again.select(t_again, inf), t_side);
        let t_side = real.select(t_side, inf);

        // The planes z = he and z = 0 (a ray on a plane, having just left it, is not met again).
        let t_top = (he - oz) * inv_dz;
        let t_bottom = -oz * inv_dz;
        let (xt, yt) = (ox + t_top * dx, oy + t_top * dy);
        let (xb, yb) = (ox + t_bottom * dx, oy + t_bottom * dy);
        let top_ok = t_top
            .gt(zero)
            .and((xt * xt + yt * yt).le(rv2))
            .and_not(left_top);
        let bottom_plane = t_bottom.gt(zero).and_not(left_bottom);
        let bottom_ok = bottom_plane.and((xb * xb + yb * yb).le(rv2));

        // Nearest water face: side (0), top (1), bottom (2); ties keep the earlier.
        let mut t_water = t_side;
        let mut water_face = zero;
        let m = top_ok.and(t_top.lt(t_water));
        t_water = m.select(t_top, t_water);
        water_face = m.select(F8::splat(1.0), water_face);
        let m = bottom_ok.and(t_bottom.lt(t_water));
        t_water = m.select(t_bottom, t_water);
        water_face = m.select(F8::splat(2.0), water_face);
        t_water = water_on.select(t_water, inf);

        // Straw side (opaque: only the entering root, or at once for a ray that starts inside
        // it by rounding), top cap, bottom cap.
        let (px, py) = (ox - sx, oy - sy);
        let bs = px * dx + py * dy;
        let cs = px * px + py * py - rp2;
        let discs = bs * bs - a * cs;
        let near_straw = alive.and(discs.ge(zero));
        // No live ray's line passes within the straw's radius: no straw face can be hit
        // (its caps lie inside that circle); skip the work.
        let (t_straw, straw_code) = if near_straw.any() {
            let ts = (-bs - discs.max(zero).sqrt()) * inv_a;
            let inside = cs.lt(zero).and(oz.ge(zero)).and(oz.le(hp));
            let ts = inside.select(zero, ts);
            let zs = oz + ts * dz;
            let side_ok = discs
                .ge(zero)
                .and(ts.gt(zero).or(inside))
                .and(zs.ge(zero))
                .and(zs.le(hp));
            let mut t_straw = side_ok.select(ts, inf);
            // Section of the side hit, 1..=5: one plus the section boundaries below the hit.
            let mut straw_code = F8::splat(1.0);
            for k in 1..SECTION_COUNT {
                let above = zs.ge(F8::splat((k as f64 * SECTION_HEIGHT) as f32));
                straw_code = above.select(straw_code + F8::splat(1.0), straw_code);
            }
            let t_cap = (hp - oz) * inv_dz;
            let (xc, yc) = (ox + t_cap * dx - sx, oy + t_cap * dy - sy);
            let m = t_cap
                .gt(zero)
                .and((xc * xc + yc * yc).le(rp2))
                .and(t_cap.lt(t_straw));
            t_straw = m.select(t_cap, t_straw);
            straw_code = m.select(F8::splat(SECTION_COUNT as f32), straw_code);
            let (xs, ys) = (xb - sx, yb - sy);
            let m = bottom_plane
                .and((xs * xs + ys * ys).le(rp2))
                .and(t_bottom.lt(t_straw));
            t_straw = m.select(t_bottom, t_straw);
            straw_code = m.select(F8::splat(1.0), straw_code);
            (t_straw, straw_code)
        } else {
            (inf, zero)
        };

        Some(Hit8 {
            t_water,
            water_face,
            t_straw,
            straw_code,
        })
    }

    /// Where eight rays meet the water face at `t_water`, and their refracted and mirrored
    /// directions there (`total` where Snell's law forbids refraction).
    #[inline(always)]
    fn bend8(&self, o: [F8; 3], d: [F8; 3], t_water: F8, water_face: F8, in_water: M8) -> Bend8 {
        let zero = F8::splat(0.0);
        let inv_rv = F8::splat((1.0 / GLASS_RADIUS) as f32);
        let [ox, oy, oz] = o;
        let [dx, dy, dz] = d;
        let t = t_water;
        let (qx, qy, qz) = (ox + t * dx, oy + t * dy, oz + t * dz);
        let is_side = water_face.lt(F8::splat(0.5));
        let is_top = water_face.lt(F8::splat(1.5)).and_not(is_side);
        let (nx, ny) = (
            is_side.select(qx * inv_rv, zero),
            is_side.select(qy * inv_rv, zero),
        );
        let nz = is_side.select(zero, is_top.select(F8::splat(1.0), F8::splat(-1.0)));
        // The side's normal q/Rv is unit to rounding (q lies on the wall): not renormalised.
        let cos_raw = -(dx * nx + dy * ny + dz * nz);
        let facing = cos_raw.ge(zero);
        let (mx, my, mz) = (
            facing.select(nx, -nx),
            facing.select(ny, -ny),
            facing.select(nz, -nz),
        );
        let cos_i = facing.select(cos_raw, -cos_raw);
        let eta = in_water.select(F8::splat(self.eta_into_air), F8::splat(self.eta_into_water));
        let sin2_t = eta * eta * (F8::splat(1.0) - cos_i * cos_i);
        let total = sin2_t.gt(F8::splat(1.0));
        let cos_t = (F8::splat(1.0) - sin2_t).max(zero).sqrt();
        let k = eta * cos_i - cos_t;
        let (rx, ry, rz) = (eta * dx + k * mx, eta * dy + k * my, eta * dz + k * mz);
        // Snell's refracted direction is unit when d and the normal are; the rounding drift
        // over at most a few events (~1e-7) is far below what changes a pixel.
        // Mirror: d + 2·cos_i·m (m faces the incoming ray).
        let two_cos = F8::splat(2.0) * cos_i;
        let (lx, ly, lz) = (dx + two_cos * mx, dy + two_cos * my, dz + two_cos * mz);
        Bend8 {
            q: [qx, qy, qz],
            refracted: [rx, ry, rz],
            reflected: [lx, ly, lz],
            total,
            is_top,
            cos_i,
            cos_t,
        }
    }
}

/// How one branch of a pixel's ray ends ([`PacketTracer::branch_ends_row`]), in single precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BranchEnd {
    /// On the straw.
    Straw {
        /// Colour code of the section, 1..=5.
        code: u8,
        /// The straw point reached.
        point: [f32; 3],
        /// The branch's weight.
        weight: f32,
    },
    /// Out of the scene along its last straight piece.
    Escaped {
        /// Where the last piece starts (the eye or the last event).
        origin: [f32; 3],
        /// Its unit direction.
        direction: [f32; 3],
        /// The branch's weight.
        weight: f32,
    },
    /// It would need more events than allowed.
    Dropped {
        /// The branch's weight.
        weight: f32,
    },
}

/// The nearest faces ahead of eight rays.
#[derive(Clone, Copy, Debug)]
struct Hit8 {
    /// Distance to the nearest water face (infinite: none).
    t_water: F8,
    /// Which: 0 side, 1 top, 2 bottom.
    water_face: F8,
    /// Distance to the nearest straw face (infinite: none).
    t_straw: F8,
    /// The colour code there.
    straw_code: F8,
}

/// Eight rays at a water face.
#[derive(Clone, Copy, Debug)]
struct Bend8 {
    /// The points met.
    q: [F8; 3],
    /// Refracted directions (meaningless where `total`).
    refracted: [F8; 3],
    /// Mirrored directions.
    reflected: [F8; 3],
    /// Total reflection.
    total: M8,
    /// The face is the water's top.
    is_top: M8,
    /// Cosine of incidence, and of refraction.
    cos_i: F8,
    cos_t: F8,
}

/// The rays through the centres of pixels `8p .. 8p + 8` of row `row` (SPEC §6: `f + sx·r + sy·u`,
/// `sx` affine in the column): origins, unit directions and which lanes can meet the scene.
///
/// Near the scene, in single precision from the eye. Farther than [`FAR_EYE`], each ray is made in
/// double precision ([`Camera::pixel_ray`]) and started where it enters the bounding sphere.
#[inline(always)]
fn row_rays(camera: &Camera, row: u32) -> impl Fn(usize) -> ([F8; 3], [F8; 3], M8) + '_ {
    let (w, h) = (camera.width as f64, camera.height as f64);
    let sx_scale = camera.tan_half_fov * (w / h);
    let sy = ((1.0 - 2.0 * (row as f64 + 0.5) / h) * camera.tan_half_fov) as f32;
    let sx_step = (2.0 / w * sx_scale) as f32;
    let sx_start = (sx_scale * (1.0 / w - 1.0)) as f32; // pixel 0's centre
    let v = |x: Vec3| [x.x as f32, x.y as f32, x.z as f32];
    let (f, r, u) = (v(camera.forward), v(camera.right), v(camera.up));
    // The row's part common to all pixels: f + sy·u.
    let base = [f[0] + sy * u[0], f[1] + sy * u[1], f[2] + sy * u[2]];
    let lane = F8(std::array::from_fn(|k| k as f32));
    let eye = v(camera.eye);
    let far = (camera.eye - BOUNDING_CENTRE).length() > FAR_EYE;
    move |p: usize| {
        if far {
            let mut o = [[0.0f32; LANES]; 3];
            let mut d = [[0.0f32; LANES]; 3];
            let mut alive = [0u32; LANES];
            for k in 0..LANES {
                // Columns past the picture's edge are traced (and ignored) like any other.
                let ray = camera.pixel_ray(row, (p * LANES + k) as u32);
                // A ray that misses the scene keeps the eye and its direction (a picture still
                // shows what lies behind), but is not traced.
                let start = enter_bounding_sphere(ray);
                let start_ray = start.map_or(ray, |(r, _)| r);
                for (c, (x, y)) in v(start_ray.origin)
                    .into_iter()
                    .zip(v(start_ray.direction))
                    .enumerate()
                {
                    o[c][k] = x;
                    d[c][k] = y;
                }
                if start.is_some() {
                    alive[k] = u32::MAX;
                }
            }
            return (o.map(F8), d.map(F8), M8(alive));
        }
        let first = F8::splat((p * LANES) as f32);
        let sx = F8::splat(sx_start) + (first + lane) * F8::splat(sx_step);
        let dx = F8::splat(base[0]) + sx * F8::splat(r[0]);
        let dy = F8::splat(base[1]) + sx * F8::splat(r[1]);
        let dz = F8::splat(base[2]) + sx * F8::splat(r[2]);
        let inv = F8::splat(1.0) / (dx * dx + dy * dy + dz * dz).sqrt();
        (
            [F8::splat(eye[0]), F8::splat(eye[1]), F8::splat(eye[2])],
            [dx * inv, dy * inv, dz * inv],
            M8::splat(true),
        )
    }
}

/// Reusable buffers for [`PacketTracer::fresnel_row`] (keep one per thread).
#[derive(Clone, Debug, Default)]
pub struct FresnelWave {
    current: Branches,
    next: Branches,
    /// Ray segments followed so far for each pixel of the row (bounded by
    /// [`FRESNEL_SEGMENTS_PER_RAY`]).
    segments: Vec<u32>,
    /// The eye of the rays being followed, in single precision.
    eye: [f32; 3],
}

/// Fresnel branches, structure of arrays: origin and direction components, weight, medium, pixel.
///
/// The vectors only grow (to the largest wave seen) and are written by index: `len` counts the
/// branches in use, so pushing is a plain store.
#[derive(Clone, Debug, Default)]
struct Branches {
    /// `ox, oy, oz, dx, dy, dz`.
    ray: [Vec<f32>; 6],
    w: Vec<f32>,
    in_water: Vec<bool>,
    pixel: Vec<u32>,
    /// The water face each branch starts on (as [`Hit8::water_face`], or [`NO_FACE`]).
    left: Vec<f32>,
    len: usize,
}

impl Branches {
    fn clear(&mut self) {
        self.len = 0;
    }

    fn len(&self) -> usize {
        self.len
    }

    /// Makes room for `n` branches in all.
    fn reserve_total(&mut self, n: usize) {
        if self.w.len() < n {
            let n = n.max(2 * self.w.len());
            for v in &mut self.ray {
                v.resize(n, 0.0);
            }
            self.w.resize(n, 0.0);
            self.in_water.resize(n, false);
            self.pixel.resize(n, 0);
            self.left.resize(n, NO_FACE);
        }
    }

    /// Appends a branch; room must have been made with [`Self::reserve_total`].
    #[inline(always)]
    fn push(&mut self, o: [f32; 3], d: [f32; 3], w: f32, in_water: bool, pixel: u32, left: f32) {
        let n = self.len;
        for (k, x) in o.into_iter().chain(d).enumerate() {
            self.ray[k][n] = x;
        }
        self.w[n] = w;
        self.in_water[n] = in_water;
        self.pixel[n] = pixel;
        self.left[n] = left;
        self.len = n + 1;
    }

    /// The faces branches `base .. base + 8` start on ([`NO_FACE`] past the end).
    #[inline(always)]
    fn load_left(&self, base: usize) -> F8 {
        let v = &self.left[..self.len];
        match v.get(base..base + LANES) {
            Some(full) => F8(std::array::from_fn(|k| full[k])),
            None => F8(std::array::from_fn(|k| {
                v.get(base + k).copied().unwrap_or(NO_FACE)
            })),
        }
    }

    /// Component `c` of branches `base .. base + 8` (a harmless 0.5 past the end).
    #[inline(always)]
    fn load(&self, c: usize, base: usize) -> F8 {
        let v = &self.ray[c][..self.len];
        match v.get(base..base + LANES) {
            Some(full) => F8(std::array::from_fn(|k| full[k])),
            None => F8(std::array::from_fn(|k| {
                v.get(base + k).copied().unwrap_or(0.5)
            })),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::REFERENCES;
    use crate::Vec3;

    /// The AVX2 build and the portable build give the same pixels (same IEEE operations).
    #[test]
    fn avx2_and_portable_agree() {
        #[cfg(target_arch = "x86_64")]
        let has_avx2 = std::is_x86_feature_detected!("avx2");
        #[cfg(not(target_arch = "x86_64"))]
        let has_avx2 = false;
        if !has_avx2 {
            // Both calls would run the portable code: comparing it with itself proves nothing.
            // (The packet pictures are checked against the double-precision tracer elsewhere.)
            eprintln!(
                "skipped: this processor has no AVX2, so there is no second build to compare"
            );
            return;
        }
        for r in REFERENCES {
            let scene = r.scene(1.333);
            let target = Vec3::new(r.straw.0, r.straw.1, r.water_height);
            let cam = Camera::new(r.observer, target, 203, 61, 50f64.to_radians());
            let pt = PacketTracer::new(&scene);
            for i in 0..cam.height {
                let mut a = vec![0u8; cam.width as usize];
                let mut b = vec![0u8; cam.width as usize];
                pt.course_row(&cam, i, &mut a);
                pt.course_row_portable(&cam, i, &mut b);
                assert_eq!(a, b, "row {i}");
                let mut wave = FresnelWave::default();
                let mut fa = vec![[0.0; SECTION_COUNT]; cam.width as usize];
                let mut fb = fa.clone();
                pt.fresnel_row(&cam, i, 1e-4, &mut wave, &mut fa);
                pt.fresnel_row_portable(&cam, i, 1e-4, &mut wave, &mut fb);
                assert_eq!(fa, fb, "fresnel row {i}");
            }
        }
    }
}
