// plait::geometry::strands — every strand drawn, each standing for itself.
#define_import_path plait::geometry::strands

fn strand_weight(strand_id: u32) -> f32 {
    return 1.0;
}
