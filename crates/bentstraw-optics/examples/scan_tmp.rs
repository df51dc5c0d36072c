use bentstraw_optics::apparent::eye_model_points;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::REFERENCES;
fn main() {
    for r in REFERENCES {
        let scene = r.scene(1.333);
        let cloud = sample_image(&scene, r.observer, 20000, &|_| {});
        let mut eye = eye_model_points(&scene, r.observer, &cloud.points);
        eye.retain(|p| p.position.is_some());
        eye.sort_by(|a, b| {
            b.gap_to_course()
                .unwrap()
                .total_cmp(&a.gap_to_course().unwrap())
        });
        let n = eye.len();
        println!(
            "ref {} : quantiles gap 50% {:.4} 90% {:.4} 99% {:.4} 99.9% {:.4}",
            r.number,
            eye[n / 2].gap_to_course().unwrap(),
            eye[n / 10].gap_to_course().unwrap(),
            eye[n / 100].gap_to_course().unwrap(),
            eye[n / 1000].gap_to_course().unwrap()
        );
        for p in eye.iter().take(4) {
            println!(
                "  gap {:.4} L {:.4} s_h {:?} s_v {:?} ev {} col {} dir {:.4?}",
                p.gap_to_course().unwrap(),
                p.image.path_length,
                p.s_h,
                p.s_v,
                p.image.events,
                p.image.color,
                p.image.direction
            );
        }
    }
}
