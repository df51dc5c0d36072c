//! The single-precision packet tracer for pictures: eight rays at a time, structure of arrays,
//! branch-free, so that the compiler maps each step onto one 8-wide SIMD instruction.
//!
//! The physics is the world's one rule ([`World`]'s nearest surface and what light does there,
//! written once over [`Real`] and compiled here for [`F8`]): the same surfaces, the same
//! exclusion of the face a ray has just left, the same opaque objects, for the assignment's glass
//! and for every scene file. Only the arithmetic differs (f32, good to ~1e-8 m at the scale of
//! the glass). A pixel's colour can therefore differ from the double-precision tracer's only where
//! the answer changes within a hair of the ray: on the picture's colour boundaries. The tests
//! bound how many pixels differ and check that they all lie on boundaries. Image points never use
//! this path; they stay in double precision.
//!
//! An eye farther than [`FAR_EYE`] from the scene cannot be written in f32 to the precision the
//! glass needs (at 1 km an f32 is good to 6e-5 m): each ray is then made in double precision and
//! brought to the scene's bounding sphere before it is rounded to f32, so a far view is as sharp
//! as a near one.
//!
//! The same generic code is compiled three times: for AVX-512 and for AVX2 (chosen at run time
//! with `is_x86_feature_detected!`), with the eight lanes in one AVX register
//! ([`crate::lanes::avx`], each operation one instruction), and for the baseline target, with the
//! lanes as an array ([`F8`]) or, in WebAssembly with SIMD, in two 4-lane registers
//! ([`crate::lanes::BaselinePacket`]). Course pictures on AVX-512 follow thirty-two rays at a
//! time, in two AVX-512 registers ([`crate::lanes::avx512`]): each step is bound by the latency
//! of the step before, so two independent packets of sixteen, their instructions interleaved,
//! keep the core busy. All use the same IEEE operations in the same order (no fused multiply-add), so all
//! give the same pixels (tested on every gallery scene).

use crate::camera::Camera;
use crate::geometry::{enter_sphere, Ray};
#[cfg(target_arch = "x86_64")]
use crate::lanes::avx::F8Avx;
#[cfg(target_arch = "x86_64")]
use crate::lanes::avx512::{F32Avx512 as Wider, Wide};
use crate::lanes::{BaselinePacket, Mask, Packet, PacketMask, Real, F8, V3};
use crate::world::fresnel::{followed_lanes, prune_threshold, split, SegmentBudget};
use crate::world::FRESNEL_SEGMENTS_PER_RAY;
use crate::world::{World, AIR};
use crate::Vec3;

pub use crate::lanes::LANES;

/// Distance (m) from the scene's centre beyond which an eye's rays are made in double precision
/// and started on the scene's bounding sphere.
pub const FAR_EYE: f64 = 1.0;

/// Code of "nothing" in a lane's record of what it has just left.
const NO_FACE: f32 = -1.0;

/// Which compilation of the packet code a processor runs: the same generic code, the same IEEE
/// operations in the same order (no fused multiply-add), so the same pixels, compiled for the
/// widest instruction set it has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Instructions {
    /// x86-64 with AVX-512 (VL): the same 8-lane operations, with twice the registers, and
    /// course rows thirty-two lanes at a time.
    Avx512,
    /// x86-64 with AVX2.
    Avx2,
    /// The baseline instruction set of the target.
    Baseline,
}

impl Instructions {
    /// The widest this processor has.
    pub fn detect() -> Instructions {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512vl")
            {
                return Instructions::Avx512;
            }
            if std::is_x86_feature_detected!("avx2") {
                return Instructions::Avx2;
            }
        }
        Instructions::Baseline
    }
}

/// A method that runs `$generic` compiled for the packet tracer's instruction set, with the two
/// compilations it may choose (`$avx2`, `$avx512`).
macro_rules! compiled {
    ($(#[$doc:meta])* pub fn $name:ident $(<const $g:ident: usize>)? (&self $(, $arg:ident: $ty:ty)* $(,)?)
        => $generic:ident, $avx2:ident, $avx512:ident) => {
        $(#[$doc])*
        #[allow(clippy::too_many_arguments)]
        pub fn $name $(<const $g: usize>)? (&self $(, $arg: $ty)*) {
            match self.instructions {
                // SAFETY: the processor has these instructions ([`Instructions::detect`]).
                #[cfg(target_arch = "x86_64")]
                Instructions::Avx512 => unsafe { self.$avx512($($arg),*) },
                // SAFETY: as above.
                #[cfg(target_arch = "x86_64")]
                Instructions::Avx2 => unsafe { self.$avx2($($arg),*) },
                _ => self.$generic::<BaselinePacket $(, $g)?>($($arg),*),
            }
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2")]
        #[allow(clippy::too_many_arguments)]
        unsafe fn $avx2 $(<const $g: usize>)? (&self $(, $arg: $ty)*) {
            self.$generic::<F8Avx $(, $g)?>($($arg),*)
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        #[allow(clippy::too_many_arguments)]
        unsafe fn $avx512 $(<const $g: usize>)? (&self $(, $arg: $ty)*) {
            self.$generic::<F8Avx $(, $g)?>($($arg),*)
        }
    };
}

/// A world ready for packets.
#[derive(Clone, Debug, PartialEq)]
pub struct PacketTracer<'w> {
    world: &'w World,
    instructions: Instructions,
}

/// How one branch of a pixel's ray ends ([`PacketTracer::branch_ends_row`]), in single precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BranchEnd {
    /// On an object.
    Object {
        /// Colour code there (1..=5 a straw's bands, 6 a coin, 7 a card, 8 its picture).
        code: u8,
        /// Which object.
        object: u16,
        /// Which part of it (0 side, 1 bottom, 2 top).
        part: u8,
        /// The point reached.
        point: [f32; 3],
        /// The branch's weight.
        weight: f32,
        /// The light it lost in tinted media, per channel (it keeps `exp(−absorbed)`).
        absorbed: [f32; 3],
    },
    /// Out of the scene along its last straight piece.
    Escaped {
        /// Where the last piece starts (the eye or the last event).
        origin: [f32; 3],
        /// Its unit direction.
        direction: [f32; 3],
        /// The branch's weight.
        weight: f32,
        /// The light it lost in tinted media, per channel (it keeps `exp(−absorbed)`).
        absorbed: [f32; 3],
    },
    /// It would need more events than allowed, or more segments than its ray may follow.
    Dropped {
        /// The branch's weight.
        weight: f32,
    },
    /// It was lighter than the pruning threshold, and abandoned.
    Pruned {
        /// The branch's weight.
        weight: f32,
    },
}

/// Every lane of `v`, component by component.
#[inline(always)]
fn block_lanes<P: Packet>(v: &V3<P>) -> [[f32; LANES]; 3] {
    [v.x.to_array(), v.y.to_array(), v.z.to_array()]
}

/// The components of lane `k`.
#[inline(always)]
fn lane<P: Packet>(v: &V3<P>, k: usize) -> [f32; 3] {
    [v.x.to_array()[k], v.y.to_array()[k], v.z.to_array()[k]]
}

impl<'w> PacketTracer<'w> {
    /// Traces `world` in packets.
    pub fn new(world: &'w World) -> PacketTracer<'w> {
        PacketTracer {
            world,
            instructions: Instructions::detect(),
        }
    }

    /// The same tracer, compiled for `instructions` (which the processor must have: checked).
    pub fn with_instructions(mut self, instructions: Instructions) -> Option<PacketTracer<'w>> {
        let ok = match (instructions, Instructions::detect()) {
            (Instructions::Avx512, Instructions::Avx512) => true,
            (Instructions::Avx512, _) => false,
            (Instructions::Avx2, Instructions::Baseline) => false,
            _ => true,
        };
        self.instructions = instructions;
        ok.then_some(self)
    }

    /// The world traced.
    pub fn world(&self) -> &World {
        self.world
    }

    /// Colour codes (0 = none) of the rays through the centres of pixel row `row` of
    /// `camera`; `codes.len()` must be the camera's width.
    pub fn course_row(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        match self.instructions {
            // SAFETY: the processor has these instructions ([`Instructions::detect`]).
            #[cfg(target_arch = "x86_64")]
            Instructions::Avx512 => unsafe { self.course_row_avx512(camera, row, codes) },
            // SAFETY: as above.
            #[cfg(target_arch = "x86_64")]
            Instructions::Avx2 => unsafe { self.course_row_avx2(camera, row, codes) },
            _ => self.course_row_generic::<BaselinePacket>(camera, row, codes),
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn course_row_avx2(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        self.course_row_generic::<F8Avx>(camera, row, codes)
    }

    /// [`Self::course_row`] thirty-two rays at a time, in two AVX-512 registers: a ray's
    /// arithmetic is the eight-lane packets', so its colour is theirs.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn course_row_avx512(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        self.course_row_wide::<Wider>(camera, row, codes)
    }

    /// [`Self::course_row`] with the rays of a row in packets of `W`, near the scene.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn course_row_wide<W: Wide>(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        let rays = RowRays::new(camera, row, self.world.bounding_sphere());
        if rays.far {
            // Rays made one by one in double precision: eight at a time, as they are made.
            return self.course_row_generic::<F8Avx>(camera, row, codes);
        }
        if self.world.plain_only() {
            self.course_row_wide_in::<W, false>(&rays, codes);
        } else {
            self.course_row_wide_in::<W, true>(&rays, codes);
        }
    }

    /// [`Self::course_row_wide`]'s loop, for a world with solids or without (see
    /// [`World::nearest_lanes_in`]).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn course_row_wide_in<W: Wide, const SOLIDS: bool>(&self, rays: &RowRays, codes: &mut [u8]) {
        let zero = W::splat(0.0);
        let all = W::Mask::splat(true);
        // The next packet's rays are made while this one is traced: their square root and
        // division would otherwise start each packet with a wait.
        let mut next = rays.wide_packet::<W>(0);
        for (p, chunk) in codes.chunks_mut(W::LANES).enumerate() {
            let (o, d) = next;
            next = rays.wide_packet::<W>(p + 1);
            let ends = self.world.follow_course_in::<W, SOLIDS>(
                o,
                d,
                all,
                zero,
                self.world.max_events(),
                |_| {},
            );
            W::select(ends.reached, ends.color, zero).store_bytes(chunk);
        }
    }

    /// [`Self::course_row`] for any target (the baseline instruction set).
    pub fn course_row_portable(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        self.course_row_generic::<F8>(camera, row, codes);
    }

    #[inline(always)]
    fn course_row_generic<P: Packet>(&self, camera: &Camera, row: u32, codes: &mut [u8]) {
        let rays = RowRays::new(camera, row, self.world.bounding_sphere());
        if self.world.plain_only() {
            self.course_row_in::<P, false>(&rays, codes);
        } else {
            self.course_row_in::<P, true>(&rays, codes);
        }
    }

    /// [`Self::course_row_generic`]'s loop, for a world with solids or without (see
    /// [`World::nearest_lanes_in`]).
    #[inline(always)]
    fn course_row_in<P: Packet, const SOLIDS: bool>(&self, rays: &RowRays, codes: &mut [u8]) {
        let zero = P::splat(0.0);
        for (p, chunk) in codes.chunks_mut(LANES).enumerate() {
            let (o, d, alive) = rays.packet::<P>(p);
            let ends = self.world.follow_course_in::<P, SOLIDS>(
                o,
                d,
                alive,
                zero,
                self.world.max_events(),
                |_| {},
            );
            let code = P::select(ends.reached, ends.color, zero);
            for (c, x) in chunk.iter_mut().zip(code.to_array()) {
                *c = x as u8;
            }
        }
    }

    compiled! {
        /// Fresnel weights per colour code (the first `N` codes, 5 for the straw's
        /// sections) of the rays through the centres of pixel row `row`; `weights.len()` must be
        /// the camera's width. `wave` holds reusable buffers.
        ///
        /// Traced breadth first: every branch alive after `k` events is in one list, traced eight at a
        /// time; the list of their children is the next. So lanes stay full whatever the tree's shape.
        /// Branches lighter than `prune_below` are abandoned, branches that provably escape (out
        /// through a face of the scene's hull, or mirrored off it) are not followed, and at most
        /// [`FRESNEL_SEGMENTS_PER_RAY`] segments are followed per pixel.
        pub fn fresnel_row<const N: usize>(
            &self,
            camera: &Camera,
            row: u32,
            prune_below: f64,
            wave: &mut FresnelWave,
            weights: &mut [[f64; N]],
        ) => fresnel_row_generic, fresnel_row_avx2, fresnel_row_avx512
    }

    /// [`Self::fresnel_row`] for any target (the baseline instruction set).
    pub fn fresnel_row_portable<const N: usize>(
        &self,
        camera: &Camera,
        row: u32,
        prune_below: f64,
        wave: &mut FresnelWave,
        weights: &mut [[f64; N]],
    ) {
        self.fresnel_row_generic::<F8, N>(camera, row, prune_below, wave, weights);
    }

    #[inline(always)]
    fn fresnel_row_generic<P: Packet, const N: usize>(
        &self,
        camera: &Camera,
        row: u32,
        prune_below: f64,
        wave: &mut FresnelWave,
        weights: &mut [[f64; N]],
    ) {
        debug_assert_eq!(weights.len(), camera.width as usize);
        for w in weights.iter_mut() {
            *w = [0.0; N];
        }
        // The picture's breadth-first loop, keeping only the weight that reaches the objects.
        self.branch_ends_row_generic::<P>(
            camera,
            row,
            true,
            prune_below,
            wave,
            &mut |pixel, end| {
                if let BranchEnd::Object { code, weight, .. } = end {
                    if let Some(w) = weights[pixel].get_mut(code as usize - 1) {
                        *w += weight as f64;
                    }
                }
            },
        );
    }

    compiled! {
        /// How every branch of the rays through the centres of pixel row `row` ends, for a picture
        /// that shows what each branch meets: `on_end(pixel, end)` once per branch end.
        ///
        /// With `split` (fresnel mode) each branch splits at every interface by the Fresnel
        /// reflectance, branches lighter than `prune_below` are abandoned; without it (course mode)
        /// each ray is refracted or totally reflected, keeps weight 1, and is traced by the course's
        /// loop eight at a time. Branches that provably escape (out through a face of the scene's
        /// hull, or mirrored off it) are reported as escaping from the face at once. Fresnel branches
        /// are traced breadth first, so the lanes stay full (see [`Self::fresnel_row`], which is this
        /// loop keeping only the straw's weights).
        pub fn branch_ends_row(
            &self,
            camera: &Camera,
            row: u32,
            split: bool,
            prune_below: f64,
            wave: &mut FresnelWave,
            on_end: &mut impl FnMut(usize, BranchEnd),
        ) => branch_ends_row_generic, branch_ends_row_avx2, branch_ends_row_avx512
    }

    #[inline(always)]
    fn branch_ends_row_generic<P: Packet>(
        &self,
        camera: &Camera,
        row: u32,
        split: bool,
        prune_below: f64,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        let width = camera.width as usize;
        let eye = to_f32(camera.eye);
        let rays = RowRays::new(camera, row, self.world.bounding_sphere());
        if !split {
            for (p, start) in (0..width).step_by(LANES).enumerate() {
                let (o, d, alive) = rays.packet::<P>(p);
                let n = LANES.min(width - start);
                let on_end = &mut |k, end| on_end(start + k, end);
                if self.world.plain_only() {
                    self.course_ends::<P, false>(eye, o, d, alive, n, on_end);
                } else {
                    self.course_ends::<P, true>(eye, o, d, alive, n, on_end);
                }
            }
            return;
        }
        wave.eye = eye;
        let cur = &mut wave.current;
        cur.clear();
        cur.reserve_total(width);
        for (p, chunk_start) in (0..width).step_by(LANES).enumerate() {
            let (o, d, alive) = rays.packet::<P>(p);
            for k in 0..LANES.min(width - chunk_start) {
                let direction = lane(&d, k);
                if !alive.lane(k) {
                    // Misses the scene: straight on to the backdrop.
                    on_end(
                        chunk_start + k,
                        BranchEnd::Escaped {
                            origin: eye,
                            direction,
                            weight: 1.0,
                            absorbed: [0.0; 3],
                        },
                    );
                    continue;
                }
                cur.push(
                    lane(&o, k),
                    direction,
                    1.0,
                    AIR as f32,
                    (chunk_start + k) as u32,
                    NO_FACE,
                );
            }
        }
        let segments = FRESNEL_SEGMENTS_PER_RAY;
        self.follow_in_world::<P, _>(prune_below, segments, width, wave, on_end);
    }

    /// [`Self::follow_branches`] compiled for this world: with or without solids, and with or
    /// without media that absorb (a world without tints then carries no lost light at all).
    #[inline(always)]
    fn follow_in_world<P: Packet, E: FnMut(usize, BranchEnd)>(
        &self,
        prune_below: f64,
        max_segments: u32,
        pixels: usize,
        wave: &mut FresnelWave,
        on_end: &mut E,
    ) {
        let (p, m) = (prune_below, max_segments);
        match (self.world.plain_only(), self.world.absorbs()) {
            (true, false) => self.follow_branches::<P, E, false, false>(p, m, pixels, wave, on_end),
            (true, true) => self.follow_branches::<P, E, false, true>(p, m, pixels, wave, on_end),
            (false, false) => self.follow_branches::<P, E, true, false>(p, m, pixels, wave, on_end),
            (false, true) => self.follow_branches::<P, E, true, true>(p, m, pixels, wave, on_end),
        }
    }

    /// How the course rays of the `n` first lanes of `(o, d, alive)` end, told to `on_end` with
    /// their lane; `eye` is where they come from (a ray that meets nothing is the ray from it).
    #[inline(always)]
    fn course_ends<P: Packet, const SOLIDS: bool>(
        &self,
        eye: [f32; 3],
        o: V3<P>,
        d: V3<P>,
        alive: P::Mask,
        n: usize,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        let ends = self.world.follow_course_in::<P, SOLIDS>(
            o,
            d,
            alive,
            P::splat(0.0),
            self.world.max_events(),
            |_| {},
        );
        let (color, object, part) = (
            ends.color.to_array(),
            ends.object.to_array(),
            ends.part.to_array(),
        );
        let events = ends.events.to_array();
        let density = ends.density.map(|c| c.to_array());
        for k in 0..n {
            let absorbed = [density[0][k], density[1][k], density[2][k]];
            let end = if ends.reached.lane(k) {
                BranchEnd::Object {
                    code: color[k] as u8,
                    object: object[k] as u16,
                    part: part[k] as u8,
                    point: lane(&ends.point, k),
                    weight: 1.0,
                    absorbed,
                }
            } else if ends.dropped.lane(k) {
                BranchEnd::Dropped { weight: 1.0 }
            } else {
                BranchEnd::Escaped {
                    origin: if events[k] == 0.0 {
                        eye
                    } else {
                        lane(&ends.origin, k)
                    },
                    direction: lane(&ends.direction, k),
                    weight: 1.0,
                    absorbed,
                }
            };
            on_end(k, end);
        }
    }

    compiled! {
        /// [`Self::branch_ends_row`] for any rays from `eye` along unit `directions`, each following
        /// at most `max_segments` segments; `on_end` is given the index of the ray in `directions`.
        pub fn branch_ends(
            &self,
            eye: Vec3,
            directions: &[Vec3],
            split: bool,
            prune_below: f64,
            max_segments: u32,
            wave: &mut FresnelWave,
            on_end: &mut impl FnMut(usize, BranchEnd),
        ) => branch_ends_generic, branch_ends_avx2, branch_ends_avx512
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn branch_ends_generic<P: Packet>(
        &self,
        eye: Vec3,
        directions: &[Vec3],
        split: bool,
        prune_below: f64,
        max_segments: u32,
        wave: &mut FresnelWave,
        on_end: &mut impl FnMut(usize, BranchEnd),
    ) {
        let (centre, radius) = self.world.bounding_sphere();
        let far = (eye - centre).length() > FAR_EYE;
        // Where each ray starts: a far eye's rays on the bounding sphere, made in double
        // precision; `None` for a ray that misses the scene.
        let start = |d: Vec3| {
            if far {
                enter_sphere(
                    Ray {
                        origin: eye,
                        direction: d,
                    },
                    centre,
                    radius,
                )
                .map(|(r, _)| r.origin)
            } else {
                Some(eye)
            }
        };
        let eye32 = to_f32(eye);
        if !split {
            for (c, chunk) in directions.chunks(LANES).enumerate() {
                let mut o = [[0.0f32; LANES]; 3];
                let mut d = [[0.0f32; LANES]; 3];
                let mut alive = [false; LANES];
                for (k, &dir) in chunk.iter().enumerate() {
                    let origin = start(dir);
                    let (a, b) = (to_f32(origin.unwrap_or(eye)), to_f32(dir));
                    for i in 0..3 {
                        o[i][k] = a[i];
                        d[i][k] = b[i];
                    }
                    alive[k] = origin.is_some();
                }
                let v = |a: [[f32; LANES]; 3]| {
                    V3::new(
                        P::from_array(a[0]),
                        P::from_array(a[1]),
                        P::from_array(a[2]),
                    )
                };
                let alive = P::Mask::from_lanes(alive);
                // (Rays in any directions, a few at a time: the one kernel for every world.)
                self.course_ends::<P, true>(
                    eye32,
                    v(o),
                    v(d),
                    alive,
                    chunk.len(),
                    &mut |k, end| on_end(c * LANES + k, end),
                );
            }
            return;
        }
        wave.eye = eye32;
        let cur = &mut wave.current;
        cur.clear();
        cur.reserve_total(directions.len());
        for (k, &d) in directions.iter().enumerate() {
            match start(d) {
                Some(o) => cur.push(to_f32(o), to_f32(d), 1.0, AIR as f32, k as u32, NO_FACE),
                None => on_end(
                    k,
                    BranchEnd::Escaped {
                        origin: eye32,
                        direction: to_f32(d),
                        weight: 1.0,
                        absorbed: [0.0; 3],
                    },
                ),
            }
        }
        let pixels = directions.len();
        self.follow_in_world::<P, _>(prune_below, max_segments, pixels, wave, on_end);
    }

    /// Follows the Fresnel branches in `wave.current` to their ends, breadth first (see
    /// [`Self::branch_ends_row`]), at most `max_segments` segments for each of the `pixels`
    /// pixels (what still travels then is dropped).
    #[inline(always)]
    fn follow_branches<
        P: Packet,
        E: FnMut(usize, BranchEnd),
        const SOLIDS: bool,
        const ABSORBS: bool,
    >(
        &self,
        prune_below: f64,
        max_segments: u32,
        pixels: usize,
        wave: &mut FresnelWave,
        on_end: &mut E,
    ) {
        let world = self.world;
        let eye = wave.eye;
        let segments = &mut wave.segments;
        segments.clear();
        segments.resize(pixels, SegmentBudget::new(max_segments));
        let first_object = world.boundaries().len() as f32;
        let inf = P::splat(f64::INFINITY);
        let threshold = P::from_array([prune_threshold(prune_below); LANES]);
        let (cur, next) = (&mut wave.current, &mut wave.next);
        // Known when compiled: a world without tints traces no lost light.
        let absorbs = ABSORBS;
        if absorbs {
            cur.clear_density();
        }
        for event in 0..=world.max_events() {
            if cur.len() == 0 {
                break;
            }
            next.clear();
            next.reserve_total(2 * cur.len());
            for (b, (block, n)) in cur.packets().enumerate() {
                let alive = P::Mask::first(n);
                // The light each branch has lost so far, and (below) on this piece too: none in a
                // world without tints.
                let mut lost = if absorbs {
                    cur.density[b]
                } else {
                    [[0.0; LANES]; 3]
                };
                let lost_by =
                    |lost: &[[f32; LANES]; 3], k: usize| [lost[0][k], lost[1][k], lost[2][k]];
                let r = &block.ray;
                let o = V3::new(
                    P::from_array(r[0]),
                    P::from_array(r[1]),
                    P::from_array(r[2]),
                );
                let d = V3::new(
                    P::from_array(r[3]),
                    P::from_array(r[4]),
                    P::from_array(r[5]),
                );
                let left = P::from_array(block.left);
                // The block's rays as the arrays they were loaded from (a closure does not inherit
                // this function's vector instructions: it reads them, it does not make them).
                let (oa, da) = (&r[..3], &r[3..]);
                let escape = |k: usize, absorbed: [f32; 3], on_end: &mut E| {
                    // A branch that met nothing is the ray from the eye (a far eye's rays start
                    // on the bounding sphere, possibly past the backdrop's floor).
                    let origin = if block.left[k] == NO_FACE {
                        eye
                    } else {
                        [oa[0][k], oa[1][k], oa[2][k]]
                    };
                    on_end(
                        block.pixel[k] as usize,
                        BranchEnd::Escaped {
                            origin,
                            direction: [da[0][k], da[1][k], da[2][k]],
                            weight: block.w[k],
                            absorbed,
                        },
                    )
                };
                let Some(hit) = world.nearest_lanes_in::<P, SOLIDS>(o, d, alive, left) else {
                    for k in alive.lanes() {
                        escape(k, lost_by(&lost, k), on_end);
                    }
                    continue;
                };
                let met = alive.and(hit.t.lt(inf));
                let on_object = met.and(hit.code.ge(P::splat(first_object as f64)));
                let on_boundary = met.and_not(on_object);
                // (Only the lanes that met something travelled a piece: the others' stays.)
                if absorbs {
                    let mut density = lost.map(P::from_array);
                    world.absorb_lanes(P::from_array(block.medium), hit.t, met, &mut density);
                    lost = density.map(|c| c.to_array());
                }
                let absorbed = |k: usize| lost_by(&lost, k);
                if on_object.any() {
                    let color = hit.color(world, on_object).to_array();
                    let (t, code, part) =
                        (hit.t.to_array(), hit.code.to_array(), hit.part.to_array());
                    for k in on_object.lanes() {
                        let t = t[k];
                        let [ox, oy, oz] = [oa[0][k], oa[1][k], oa[2][k]];
                        let [dx, dy, dz] = [da[0][k], da[1][k], da[2][k]];
                        on_end(
                            block.pixel[k] as usize,
                            BranchEnd::Object {
                                code: color[k] as u8,
                                object: (code[k] - first_object) as u16,
                                part: part[k] as u8,
                                point: [ox + t * dx, oy + t * dy, oz + t * dz],
                                weight: block.w[k],
                                absorbed: absorbed(k),
                            },
                        );
                    }
                }
                for k in alive.and_not(met).lanes() {
                    escape(k, absorbed(k), on_end);
                }
                if event == world.max_events() {
                    for k in on_boundary.lanes() {
                        let weight = block.w[k];
                        on_end(block.pixel[k] as usize, BranchEnd::Dropped { weight });
                    }
                    continue;
                }
                if !on_boundary.any() {
                    continue;
                }
                let q = o.along(hit.t, d);
                let b = world.bend_lanes_in::<P, SOLIDS>(
                    hit.code,
                    on_boundary,
                    q,
                    d,
                    P::from_array(block.medium),
                );
                let (wr, wt) = split(P::from_array(block.w), b.reflectance(), b.total);
                let (keep_r, keep_t) =
                    (followed_lanes(wr, threshold), followed_lanes(wt, threshold));
                // Each lane's numbers, taken out of the registers once.
                let (wr, wt) = (wr.to_array(), wt.to_array());
                let (surface, beyond) = (b.surface.to_array(), b.beyond.to_array());
                let (q, reflected, refracted) = (
                    block_lanes(&q),
                    block_lanes(&b.reflected),
                    block_lanes(&b.refracted),
                );
                for k in on_boundary.lanes() {
                    let pixel = block.pixel[k];
                    let q = [q[0][k], q[1][k], q[2][k]];
                    let face = surface[k];
                    for (weight, kept, directions, escapes, medium) in [
                        (
                            wr[k],
                            keep_r.lane(k),
                            &reflected,
                            b.reflected_escapes.lane(k),
                            block.medium[k],
                        ),
                        (
                            wt[k],
                            keep_t.lane(k),
                            &refracted,
                            b.refracted_escapes.lane(k),
                            beyond[k],
                        ),
                    ] {
                        if !kept {
                            if weight > 0.0 {
                                on_end(pixel as usize, BranchEnd::Pruned { weight });
                            }
                            continue;
                        }
                        let dir = [directions[0][k], directions[1][k], directions[2][k]];
                        if !escapes && !segments[pixel as usize].spend() {
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
                                    absorbed: absorbed(k),
                                },
                            );
                        } else {
                            next.push(q, dir, weight, medium, pixel, face);
                            if absorbs {
                                next.set_last_density(absorbed(k));
                            }
                        }
                    }
                }
            }
            std::mem::swap(cur, next);
        }
    }
}

/// `v` rounded to single precision.
#[inline(always)]
fn to_f32(v: Vec3) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// The rays through the centres of the pixels of one row of a camera's picture (directions
/// `f + sx·r + sy·u`, `sx` affine in the column), eight at a time ([`RowRays::packet`]).
struct RowRays<'c> {
    camera: &'c Camera,
    row: u32,
    /// `sx` of pixel 0's centre and its step from one column to the next.
    sx_start: f32,
    sx_step: f32,
    /// The row's part common to all pixels, `f + sy·u`, and `r`.
    base: [f32; 3],
    right: [f32; 3],
    eye: [f32; 3],
    /// The scene's bounding sphere, and whether the eye is far from it.
    sphere: (Vec3, f64),
    far: bool,
}

impl<'c> RowRays<'c> {
    /// The rays of row `row` of `camera`, for a scene in the bounding sphere `sphere`.
    fn new(camera: &'c Camera, row: u32, sphere: (Vec3, f64)) -> RowRays<'c> {
        let (w, h) = (camera.width as f64, camera.height as f64);
        let sx_scale = camera.tan_half_fov * (w / h);
        let sy = ((1.0 - 2.0 * (row as f64 + 0.5) / h) * camera.tan_half_fov) as f32;
        let (f, u) = (to_f32(camera.forward), to_f32(camera.up));
        RowRays {
            camera,
            row,
            sx_step: (2.0 / w * sx_scale) as f32,
            sx_start: (sx_scale * (1.0 / w - 1.0)) as f32,
            base: [f[0] + sy * u[0], f[1] + sy * u[1], f[2] + sy * u[2]],
            right: to_f32(camera.right),
            eye: to_f32(camera.eye),
            sphere,
            far: (camera.eye - sphere.0).length() > FAR_EYE,
        }
    }

    /// The rays through the centres of pixels `8p .. 8p + 8`: origins, unit directions and which
    /// lanes can meet the scene.
    ///
    /// Near the scene, in single precision from the eye. Farther than [`FAR_EYE`], each ray is
    /// made in double precision ([`Camera::pixel_ray`]) and started where it enters the bounding
    /// sphere.
    #[inline(always)]
    fn packet<P: Packet>(&self, p: usize) -> (V3<P>, V3<P>, P::Mask) {
        let s = |x: f32| P::from_array([x; LANES]);
        if self.far {
            return self.far_packet(p);
        }
        let lanes = P::from_array(std::array::from_fn(|k| k as f32));
        let (o, d) = self.near_rays(s, s((p * LANES) as f32) + lanes);
        (o, d, P::Mask::splat(true))
    }

    /// The eye and the unit directions of the near rays through pixel columns `column` (one
    /// per lane): one rule for the eight-lane packets and the wide ones, so both make the same
    /// rays.
    #[inline(always)]
    fn near_rays<R: Real>(&self, s: impl Fn(f32) -> R, column: R) -> (V3<R>, V3<R>) {
        let sx = s(self.sx_start) + column * s(self.sx_step);
        let (b, r) = (self.base, self.right);
        let dx = s(b[0]) + sx * s(r[0]);
        let dy = s(b[1]) + sx * s(r[1]);
        let dz = s(b[2]) + sx * s(r[2]);
        let inv = s(1.0) / (dx * dx + dy * dy + dz * dz).sqrt();
        let e = self.eye;
        (
            V3::new(s(e[0]), s(e[1]), s(e[2])),
            V3::new(dx * inv, dy * inv, dz * inv),
        )
    }

    /// [`Self::packet`] for the rays of a wide packet, pixels `Np .. Np + N`, near the scene
    /// only (the same operations lane by lane: the same rays).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn wide_packet<W: Wide>(&self, p: usize) -> (V3<W>, V3<W>) {
        debug_assert!(!self.far);
        let s = W::splat32;
        self.near_rays(s, s((p * W::LANES) as f32) + W::index())
    }

    /// [`Self::packet`] for a far eye.
    #[inline(always)]
    fn far_packet<P: Packet>(&self, p: usize) -> (V3<P>, V3<P>, P::Mask) {
        let (centre, radius) = self.sphere;
        let mut o = [[0.0f32; LANES]; 3];
        let mut d = [[0.0f32; LANES]; 3];
        let mut alive = [false; LANES];
        for k in 0..LANES {
            // Columns past the picture's edge are traced (and ignored) like any other.
            let ray = self.camera.pixel_ray(self.row, (p * LANES + k) as u32);
            // A ray that misses the scene keeps the eye and its direction (a picture still
            // shows what lies behind), but is not traced.
            let start = enter_sphere(ray, centre, radius);
            let start_ray = start.map_or(ray, |(r, _)| r);
            let (a, b) = (to_f32(start_ray.origin), to_f32(start_ray.direction));
            for c in 0..3 {
                o[c][k] = a[c];
                d[c][k] = b[c];
            }
            alive[k] = start.is_some();
        }
        let v = |a: [[f32; LANES]; 3]| {
            V3::new(
                P::from_array(a[0]),
                P::from_array(a[1]),
                P::from_array(a[2]),
            )
        };
        (v(o), v(d), P::Mask::from_lanes(alive))
    }
}

/// Reusable buffers for [`PacketTracer::fresnel_row`] (keep one per thread).
#[derive(Clone, Debug, Default)]
pub struct FresnelWave {
    current: Branches,
    next: Branches,
    /// The segments each pixel of the row may still follow (at most
    /// [`FRESNEL_SEGMENTS_PER_RAY`] in all).
    segments: Vec<SegmentBudget>,
    /// The eye of the rays being followed, in single precision.
    eye: [f32; 3],
}

thread_local! {
    /// Waves kept by each thread between tasks and pictures (see [`FresnelWave::pooled`]).
    static WAVES: std::cell::RefCell<Vec<FresnelWave>> = const { std::cell::RefCell::new(Vec::new()) };
}

impl FresnelWave {
    /// A wave of this thread's, grown by earlier rows and pictures, returned to the thread when
    /// dropped: a parallel loop that makes one per task (rayon makes a task per split of the rows)
    /// then allocates nothing once the first picture has grown them.
    pub fn pooled() -> PooledWave {
        PooledWave(Some(
            WAVES.with(|w| w.borrow_mut().pop()).unwrap_or_default(),
        ))
    }
}

/// A [`FresnelWave`] borrowed from its thread's pool ([`FresnelWave::pooled`]).
pub struct PooledWave(Option<FresnelWave>);

impl std::ops::Deref for PooledWave {
    type Target = FresnelWave;
    fn deref(&self) -> &FresnelWave {
        self.0.as_ref().expect("a pooled wave until it is dropped")
    }
}

impl std::ops::DerefMut for PooledWave {
    fn deref_mut(&mut self) -> &mut FresnelWave {
        self.0.as_mut().expect("a pooled wave until it is dropped")
    }
}

impl Drop for PooledWave {
    fn drop(&mut self) {
        if let Some(wave) = self.0.take() {
            // A thread that is ending has no pool left: the wave is then simply freed.
            let _ = WAVES.try_with(|w| w.borrow_mut().push(wave));
        }
    }
}

/// Eight Fresnel branches side by side, structure of arrays: what one packet loads.
#[derive(Clone, Copy, Debug)]
struct Block {
    /// `ox, oy, oz, dx, dy, dz` of each branch.
    ray: [[f32; LANES]; 6],
    /// Weight.
    w: [f32; LANES],
    /// The medium's id, as a number.
    medium: [f32; LANES],
    /// The code of the surface each branch starts on ([`World::nearest`]'s), or [`NO_FACE`].
    left: [f32; LANES],
    /// The pixel each branch belongs to.
    pixel: [u32; LANES],
}

impl Default for Block {
    /// Harmless lanes past the last branch: a finite ray in air that starts on nothing.
    fn default() -> Block {
        Block {
            ray: [[0.5; LANES]; 6],
            w: [0.0; LANES],
            medium: [AIR as f32; LANES],
            left: [NO_FACE; LANES],
            pixel: [0; LANES],
        }
    }
}

/// Fresnel branches in blocks of eight ([`Block`]): a packet is one block, loaded whole.
///
/// The blocks only grow (to the largest wave seen) and are written by index: `len` counts the
/// branches in use, so pushing is a plain store. Lanes of the last block past `len` hold earlier
/// branches, finite numbers that the packets' lane masks ignore.
#[derive(Clone, Debug, Default)]
struct Branches {
    blocks: Vec<Block>,
    len: usize,
    /// The light each branch has lost in tinted media, per channel, block by block: kept beside
    /// the blocks (and only written in a world that absorbs) so that other worlds load no more.
    density: Vec<[[f32; LANES]; 3]>,
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
        let blocks = n.div_ceil(LANES);
        if self.blocks.len() < blocks {
            let blocks = blocks.max(2 * self.blocks.len());
            self.blocks.resize(blocks, Block::default());
            self.density.resize(blocks, [[0.0; LANES]; 3]);
        }
    }

    /// Sets every branch's lost light to none (the first branches, from the eye).
    fn clear_density(&mut self) {
        self.density.fill([[0.0; LANES]; 3]);
    }

    /// Sets the lost light of the branch pushed last.
    #[inline(always)]
    fn set_last_density(&mut self, absorbed: [f32; 3]) {
        let n = self.len - 1;
        let (b, k) = (&mut self.density[n / LANES], n % LANES);
        for c in 0..3 {
            b[c][k] = absorbed[c];
        }
    }

    /// Appends a branch; room must have been made with [`Self::reserve_total`].
    #[inline(always)]
    fn push(&mut self, o: [f32; 3], d: [f32; 3], w: f32, medium: f32, pixel: u32, left: f32) {
        let n = self.len;
        let (b, k) = (&mut self.blocks[n / LANES], n % LANES);
        // Plain stores (a chained iterator here cost a tenth of a Fresnel picture).
        let [ox, oy, oz] = o;
        let [dx, dy, dz] = d;
        b.ray[0][k] = ox;
        b.ray[1][k] = oy;
        b.ray[2][k] = oz;
        b.ray[3][k] = dx;
        b.ray[4][k] = dy;
        b.ray[5][k] = dz;
        b.w[k] = w;
        b.medium[k] = medium;
        b.pixel[k] = pixel;
        b.left[k] = left;
        self.len = n + 1;
    }

    /// The blocks in use, each with how many of its lanes hold branches.
    #[inline(always)]
    fn packets(&self) -> impl Iterator<Item = (&Block, usize)> {
        let len = self.len;
        self.blocks[..len.div_ceil(LANES)]
            .iter()
            .enumerate()
            .map(move |(i, b)| (b, LANES.min(len - i * LANES)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{REFERENCES, SECTION_COUNT};
    use crate::Vec3;

    /// In a tinted liquid each Fresnel branch loses light by the Beer–Lambert law: seen straight
    /// down through a layer of depth `h`, a branch that crossed the layer `k` times has lost
    /// `k·α·h` in each channel, leaves downwards after odd crossings and upwards after even ones,
    /// and carries the weight the Fresnel reflectance at normal incidence gives it.
    #[cfg(feature = "scene-file")]
    #[test]
    fn fresnel_branches_lose_light_along_their_path_in_a_tinted_liquid() {
        use crate::scene_file::SceneDescription;
        let (n, h) = (1.333f64, 0.16f64);
        let text = format!(
            "[container]\nshape = \"tank\"\nhalf_x = 0.10\nhalf_y = 0.05\nheight = 0.20\n\
             [[liquid]]\nname = \"tea\"\nindex = {n}\ntop = {h}\ntint = \"#c08040\"\n"
        );
        let scene = SceneDescription::from_toml(&text).expect("a tinted tank");
        let alpha = scene.liquids[0].absorption().expect("a tint");
        // sRGB c0 is 192/255: 0.527 of the red light is kept through 10 cm.
        assert!(
            (alpha[0] - -(0.527_f64.ln()) / 0.1).abs() < 0.01,
            "{alpha:?}"
        );
        let world = World::new(&scene, 12).expect("a valid scene");
        assert!(world.absorbs());
        let tracer = PacketTracer::new(&world);
        let mut wave = FresnelWave::default();
        let r = ((n - 1.0) / (n + 1.0)).powi(2);
        let (mut seen, mut total) = (vec![0.0f64; 8], 0.0);
        let eye = Vec3::new(0.013, -0.007, 0.4);
        let down = [Vec3::new(0.0, 0.0, -1.0)];
        tracer.branch_ends(eye, &down, true, 1e-9, 4096, &mut wave, &mut |_, end| {
            let BranchEnd::Escaped {
                direction,
                weight,
                absorbed,
                ..
            } = end
            else {
                return;
            };
            let k = absorbed[0] as f64 / (alpha[0] * h);
            let crossings = k.round();
            for c in 0..3 {
                let kc = absorbed[c] as f64 / (alpha[c] * h);
                assert!((kc - crossings).abs() < 1e-4, "channel {c}: {kc} crossings");
            }
            let odd = crossings as u32 % 2 == 1;
            assert_eq!(
                odd,
                direction[2] < 0.0,
                "{crossings} crossings, {direction:?}"
            );
            // Weight: R off the top (no crossing); else in through the top (1 − R), k − 1
            // reflections inside (R each), out (1 − R).
            let expected = if crossings == 0.0 {
                r
            } else {
                (1.0 - r).powi(2) * r.powi(crossings as i32 - 1)
            };
            assert!(
                (weight as f64 - expected).abs() < 1e-5 * expected.max(1e-3),
                "{crossings} crossings: weight {weight}, expected {expected}"
            );
            if (crossings as usize) < seen.len() {
                seen[crossings as usize] += weight as f64;
            }
            total += weight as f64;
        });
        assert!(seen[..4].iter().all(|&w| w > 0.0), "{seen:?}");
        assert!((total - 1.0).abs() < 1e-5, "{total}");
    }

    /// Every branch end of a Fresnel picture's rows is told, pruned and dropped light included:
    /// each pixel's weights add up to its ray's, 1 (the same policy as the double-precision
    /// tracer's, whose steps add up to 1 too).
    #[test]
    fn every_pixels_branch_weights_add_up_to_one() {
        for r in REFERENCES {
            let world = World::assignment(&r.scene(1.333));
            let cam = Camera::new(
                r.observer,
                Vec3::new(r.straw.0, r.straw.1, 0.1),
                97,
                41,
                0.9,
            );
            let tracer = PacketTracer::new(&world);
            let mut wave = FresnelWave::default();
            let (mut pruned, mut dropped) = (0.0f64, 0.0f64);
            for i in 0..cam.height {
                let mut sum = vec![0.0f64; cam.width as usize];
                tracer.branch_ends_row(&cam, i, true, 1e-3, &mut wave, &mut |j, end| {
                    sum[j] += match end {
                        BranchEnd::Object { weight, .. } | BranchEnd::Escaped { weight, .. } => {
                            weight as f64
                        }
                        BranchEnd::Dropped { weight } => {
                            dropped += weight as f64;
                            weight as f64
                        }
                        BranchEnd::Pruned { weight } => {
                            pruned += weight as f64;
                            weight as f64
                        }
                    };
                });
                for (j, s) in sum.iter().enumerate() {
                    assert!(
                        (s - 1.0).abs() < 1e-5,
                        "reference {} pixel ({i}, {j}): {s}",
                        r.number
                    );
                }
            }
            assert!(
                pruned > 0.0,
                "reference {}: some light is pruned at 1e-3",
                r.number
            );
            let _ = dropped;
        }
    }

    /// Every build the processor can run gives the portable build's pixels (same IEEE operations,
    /// eight or thirty-two lanes; 213 columns end in a partly filled packet, both of whose
    /// AVX-512 halves hold rays).
    #[test]
    fn every_instruction_set_gives_the_same_pixels() {
        let first = World::assignment(&REFERENCES[0].scene(1.333));
        let builds: Vec<Instructions> = [Instructions::Avx512, Instructions::Avx2]
            .into_iter()
            .filter(|&i| PacketTracer::new(&first).with_instructions(i).is_some())
            .collect();
        if builds.is_empty() {
            // Both calls would run the portable code: comparing it with itself proves nothing.
            // (The packet pictures are checked against the double-precision tracer elsewhere, and
            // a test of the crate fails in CI where there is no second build.)
            eprintln!(
                "skipped: this processor has no AVX2, so there is no second build to compare"
            );
            return;
        }
        for r in REFERENCES {
            let scene = World::assignment(&r.scene(1.333));
            let target = Vec3::new(r.straw.0, r.straw.1, r.water_height);
            let cam = Camera::new(r.observer, target, 213, 61, 50f64.to_radians());
            for &isa in &builds {
                let pt = PacketTracer::new(&scene).with_instructions(isa).unwrap();
                for i in 0..cam.height {
                    let mut a = vec![0u8; cam.width as usize];
                    let mut b = vec![0u8; cam.width as usize];
                    pt.course_row(&cam, i, &mut a);
                    pt.course_row_portable(&cam, i, &mut b);
                    assert_eq!(a, b, "{isa:?} row {i}");
                    let mut wave = FresnelWave::default();
                    let mut fa = vec![[0.0; SECTION_COUNT]; cam.width as usize];
                    let mut fb = fa.clone();
                    pt.fresnel_row(&cam, i, 1e-4, &mut wave, &mut fa);
                    pt.fresnel_row_portable(&cam, i, 1e-4, &mut wave, &mut fb);
                    assert_eq!(fa, fb, "{isa:?} fresnel row {i}");
                }
            }
        }
    }
}
