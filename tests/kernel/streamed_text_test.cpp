// .usda and .obj are written to their file a few MiB at a time as the text is made, not held whole
// (a trial's 21 M-hair groom.write to .usda grew to 23.8 GB and was killed). The streamed bytes are
// the whole text's, across many hand-overs: 250,000 points with widths and a curve column make
// about 10 MB of .usda.
#include "kernel/io/formats.h"

#include <gtest/gtest.h>

#include <sstream>

using namespace groom;

TEST(StreamedText, UsdaAndObjStreamedAreTheWholeTextByteForByte)
{
    const int64_t curves = 25000, points = 10;
    CurveSet cs = CurveSet::from_counts(std::vector<int64_t>(size_t(curves), points));
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) P[i] = {float(i % 977) * 0.013f, float(i) * 1e-3f, -float(i % 31) * 0.7f};
    auto W = cs.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < W.size(); ++i) W[i] = 0.008f - 1e-9f * float(i);
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    for (size_t c = 0; c < id.size(); ++c) id[c] = int64_t(c) * 7919;
    const std::string usda = io::write_usda(cs);
    ASSERT_GT(usda.size(), size_t(8) << 20);  // two hand-overs at least
    std::ostringstream streamed;
    io::stream_usda(cs, false, streamed);
    EXPECT_TRUE(streamed.str() == usda) << "streamed " << streamed.str().size() << " bytes against " << usda.size();
    const std::string obj = io::write_obj_curves(cs);
    std::ostringstream streamed_obj;
    io::stream_obj_curves(cs, false, streamed_obj);
    EXPECT_TRUE(streamed_obj.str() == obj) << "streamed " << streamed_obj.str().size() << " bytes against " << obj.size();
}
