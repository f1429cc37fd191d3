//! `hair_opaque`: no transparency — strands drawn as opaque lines with depth
//! test and write, the right-most image of Sintorn & Assarsson 2009 Fig. 2
//! ("using no transparency"). The cheapest method, and the baseline the
//! blending methods are measured against (§2.2: thin strands need alpha to
//! look thin). The draw is [`HairCoverage`] with alpha forced to 1 and no
//! alpha to coverage.
//!
//! Cost: one hair draw with early depth rejection. Memory: nothing beyond the
//! scene colour and depth it draws into.

use crate::alpha_to_coverage::HairCoverage;

pub const HAIR_OPAQUE: HairCoverage = HairCoverage {
    alpha_to_coverage: false,
};
