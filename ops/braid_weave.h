// braid_weave: where each strand of a braid lies in the braid's cross-section, as a function of the
// knot phase u (knots from the root), for every braid pattern `groom braid --pattern` offers. The
// braid op carries these offsets along the guide in its frames (lateral = binormal, height = normal).
//
// Why not the talk's formula alone (Sec. 2.1, kept as Pattern::Lissajous): with the lateral axis at
// frequency F and the height at F/2, a 3-strand braid's strand goes over four crossings and then under
// four (a rope twist, not a plait), and for 4 or 6 strands strands i and i + N/2 pass through each
// other. A plait needs the strand's height to flip at every crossing, i.e. to be decided by the
// crossings themselves. So the woven patterns are built the way braiders describe them:
//   - lateral paths: strands move between N evenly spaced slots; at every step neighbouring slots swap
//     their strands (odd-even transposition for a plait, outer piece to the other section's inside
//     for a fishtail), smoothed by a periodic Catmull-Rom spline through the slots;
//   - heights: at each crossing the pattern's rule says which strand is on top (+1) and which below
//     (-1); between its crossings a strand's height follows a cosine ease, so it is level at a crossing
//     and never passes through the other strand.
// Ropes and twists are helices; the round braid is a maypole (tubular) braid whose strands alternate
// outside / inside at each crossing.
#pragma once

#include <string>
#include <vector>

namespace groom {

enum class BraidPattern {
    Plait,      ///< flat N-strand plait: every strand alternates over / under (3 strands: the classic plait)
    Fishtail,   ///< two sections; a thin outer piece crosses its own section into the other (herringbone)
    Twist,      ///< two plies wound around each other (Senegalese twist), each ply's fibers twisted the other way
    Rope,       ///< N plies wound one way around the axis
    Round,      ///< round (tubular) braid: half the strands wind one way, half the other, over / under
    Lissajous,  ///< the talk's formula as written (Sec. 2.1): lateral at F, height at F/2
};

/// Which strand passes on top where two cross. Under (Dutch): the strand coming in from an edge passes
/// beneath, so the braid stands proud (3 strands: the strand travelling toward the middle is below).
/// Over (French / English): it passes on top. Auto: under for cornrows (orient scalp), over otherwise.
enum class BraidHand { Auto, Under, Over };

/// Every pattern, in the order braid_pattern_list() names them (cli/cmd_braid.cpp parses the names).
std::vector<BraidPattern> braid_patterns();
/// Name a pattern (the CLI's word).
const char* braid_pattern_name(BraidPattern p);
/// "plait|fishtail|twist|rope|round|lissajous", for help texts and errors.
std::string braid_pattern_list();

/// Strands a pattern uses when --strands is not given.
int default_strands(BraidPattern p);
/// Throws InvalidParam when `strands` does not suit the pattern (fishtail: even and >= 4; twist: 2;
/// round: even and >= 4; the rest >= 2; every pattern at most kMaxStrands).
void validate_pattern_strands(BraidPattern p, int strands);

/// The most strands a braid may have (the weave costs about N^3).
inline constexpr int kMaxStrands = 32;

/// One strand's place in the cross-section: x lateral in [-1, 1] (times A), y height (times B);
/// `press` in [0, 1] is 1 where the strand is pressed against another (a crossing) and 0 between.
struct WeaveOffset {
    double x = 0.0, y = 0.0;
    double press = 0.0;
};

/// The cross-section paths of one (pattern, strands, hand). Built once; at() is cheap and thread-safe.
class BraidWeave {
public:
    /// hand must not be Auto (the op resolves it from the orientation).
    BraidWeave(BraidPattern pattern, int strands, BraidHand hand);

    /// Strand i at knot phase u (any real; periodic with period 1).
    WeaveOffset at(int strand, double u) const;

    BraidPattern pattern() const { return pattern_; }
    int strands() const { return n_; }

    /// The width of a strand, in units of A, at which neighbouring strands just touch: the slot
    /// spacing of a plait or fishtail, the chord between plies of a rope, the ring for a round braid.
    double touching_width() const;
    /// The height amplitude B, in units of A, at which strands touch where they cross (plait, fishtail:
    /// crossing heights +-B put the centrelines one touching width apart; rope, twist, round: B = A, round).
    double touching_height() const;
    /// The closest approach of any two strand centrelines of a braid with lateral amplitude A, height
    /// amplitude B and knot length L (scene units) on a straight guide, measured by sampling one knot
    /// densely. The op keeps its automatic strand width under this (strands may not pass through each
    /// other), which matters when the braid is wide for its knot length.
    double min_separation(double A, double B, double knot_length) const;
    /// Direction the strands wind about the guide for helical patterns (+1: from the binormal toward
    /// the normal), 0 for the others. Fibers twist the other way in a rope or twist.
    int winding() const;

private:
    struct Event {
        double tau;   // crossing time in steps, in [0, steps)
        double value; // +1 over, -1 under
    };
    WeaveOffset slotted(int strand, double u) const;
    double slot_lateral(int strand, double tau) const;  // tau in steps, [0, steps_]

    BraidPattern pattern_;
    int n_;
    int hand_sign_;                           // +1 over, -1 under
    int steps_ = 0;                           // steps per knot (slotted patterns)
    std::vector<std::vector<int>> slots_;     // [strand][step] slot index, periodic
    std::vector<std::vector<Event>> events_;  // [strand] crossings in one period, by time
};

}  // namespace groom
