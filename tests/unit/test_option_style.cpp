// How library messages name options (io/option_style.hpp): the CLI's words unchanged by default,
// Python keywords once the Python module sets its style, from the same validation.
#include <gtest/gtest.h>

#include <string>

#include "brdfcl/error.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/render_job.hpp"
#include "io/option_style.hpp"

namespace {

using brdfcl::OptionStyle;

// The message a call throws.
template <typename F>
std::string messageOf(F&& f) {
  try {
    f();
  } catch (const brdfcl::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Sets the process's style for one test and puts the CLI's back.
class PythonStyle {
 public:
  PythonStyle() { brdfcl::setOptionStyle(OptionStyle::Python); }
  ~PythonStyle() { brdfcl::setOptionStyle(OptionStyle::Cli); }
};

}  // namespace

TEST(OptionStyle, NamesAndValuesInEitherStyle) {
  ASSERT_EQ(brdfcl::optionStyle(), OptionStyle::Cli);
  EXPECT_EQ(brdfcl::optionName("--sheen-visibility"), "--sheen-visibility");
  EXPECT_EQ(brdfcl::optionWithValue("--spp", "0"), "--spp 0");
  EXPECT_EQ(brdfcl::optionWithValue("--profile", "threejs", true), "--profile threejs");
  EXPECT_EQ(brdfcl::flagName("--allow-outside-uris"), "--allow-outside-uris");
  PythonStyle python;
  EXPECT_EQ(brdfcl::optionName("--sheen-visibility"), "sheen_visibility=");
  EXPECT_EQ(brdfcl::optionWithValue("--spp", "0"), "spp=0");
  EXPECT_EQ(brdfcl::optionWithValue("--profile", "threejs", true), "profile='threejs'");
  EXPECT_EQ(brdfcl::optionWithValue("--ibl", "'x'"), "ibl='x'");
  EXPECT_EQ(brdfcl::flagName("--allow-outside-uris"), "allow_outside_uris=True");
  // Anything that is not an option (a file's name) is left as it is.
  EXPECT_EQ(brdfcl::optionName("g.exr"), "g.exr");
  EXPECT_EQ(brdfcl::optionWithValue("g.exr", "4x4"), "g.exr 4x4");
}

TEST(OptionStyle, CliMessagesAreUnchanged) {
  EXPECT_EQ(messageOf([] { brdfcl::parseLobe("speculr"); }),
            "unknown --lobe value 'speculr'; use all, diffuse, specular, sheen or clearcoat");
  EXPECT_EQ(messageOf([] { brdfcl::checkIblSamples(0); }), "--ibl-samples 0 is out of range; use 1 to 65536");
  EXPECT_EQ(messageOf([] { brdfcl::checkIblSamplesApply(brdfcl::IblMode::SplitSum, true); }),
            "--ibl-samples applies to --ibl exact; add --ibl exact");
  EXPECT_EQ(messageOf([] { brdfcl::checkRenderSize(0, 5); }),
            "--size '0x5' is not WIDTHxHEIGHT with sides 1 to 16384, e.g. 768x768");
  EXPECT_EQ(messageOf([] { brdfcl::parseIblMode("fast"); }),
            "--ibl 'fast' is not an image-based light mode; use split-sum or exact");
}

TEST(OptionStyle, PythonMessagesNameKeywords) {
  PythonStyle python;
  EXPECT_EQ(messageOf([] { brdfcl::parseLobe("speculr"); }),
            "unknown lobe= value 'speculr'; use all, diffuse, specular, sheen or clearcoat");
  EXPECT_EQ(messageOf([] { brdfcl::parseProfile("unreal"); }),
            "unknown profile= value 'unreal'; use spec, khronos, threejs, filament, babylon or materialx");
  EXPECT_EQ(messageOf([] { brdfcl::checkIblSamples(0); }), "ibl_samples=0 is out of range; use 1 to 65536");
  EXPECT_EQ(messageOf([] { brdfcl::checkIblSamplesApply(brdfcl::IblMode::SplitSum, true); }),
            "ibl_samples= applies to ibl='exact'; add ibl='exact'");
  EXPECT_EQ(messageOf([] { brdfcl::checkRenderSpp(2000); }), "spp=2000 is out of range; use 1 to 1024");
  EXPECT_EQ(messageOf([] { brdfcl::parseIblMode("fast"); }),
            "ibl='fast' is not an image-based light mode; use split-sum or exact");
}
