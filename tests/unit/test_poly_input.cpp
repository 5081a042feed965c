// Triangle's .poly format: what is read, and that every malformed file is refused with its line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "features/poly_input.hpp"
#include "pipeline/pipeline.hpp"
#include "scratch_dir.hpp"
#include "svg/error.hpp"

namespace curvemesh::features {
namespace {

using testing_support::ScratchDir;

std::string write_temp(const ScratchDir& dir, const std::string& name, const std::string& text) {
  const auto path = dir / (name + ".poly");
  std::ofstream(path) << text;
  return path;
}

TEST(PolyInput, SquareWithDiagonalZeroBased) {
  const ScratchDir dir;
  // Through the pipeline, which resolves the parameters for the points' box.
  const auto r = pipeline::run(pipeline::Source::file(write_temp(dir, "square0",
                                                                 "# a square\n4 2 0 0\n0 0 0\n1 1 0\n\n2 1 1\n3 0 1\n"
                                                                 "5 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n4 0 2\n0\n")),
                               {}, pipeline::Stage::features);
  const features::Features& f = r.features;
  EXPECT_EQ(f.segments.size(), 5u);
  EXPECT_TRUE(f.sections.empty());
  EXPECT_TRUE(f.points.empty());
  EXPECT_EQ(f.segments[4].a, Vec2(0, 0));
  EXPECT_EQ(f.segments[4].b, Vec2(1, 1));
  EXPECT_EQ(f.segments[0].curve, -1);
  EXPECT_DOUBLE_EQ(f.lengths.d, std::sqrt(2.0));
}

TEST(PolyInput, OneBasedWithMarkersAttributesHolesAndComments) {
  const ScratchDir dir;
  const auto f = read_poly(write_temp(dir, "square1",
                                      "4 2 1 1  # attributes and markers\n1 0 0 7 1\n2 2 0 7 1\n3 2 2 7 1\n"
                                      "4 0 2 7 1\n3 1\n1 1 2 1\n2 2 3 1\n3 2 3 0  # duplicate\n"
                                      "1\n1 0.5 0.5\n"),
                           Limits{});
  EXPECT_EQ(f.segments.size(), 2u);  // the duplicate is kept once
  ASSERT_EQ(f.points.size(), 1u);    // vertex 4 is used by no segment
  EXPECT_EQ(f.points[0].p, Vec2(0, 2));
}

TEST(PolyInput, ZeroLengthSegmentBecomesAPoint) {
  const ScratchDir dir;
  const auto f =
      read_poly(write_temp(dir, "zero", "3 2 0 0\n0 0 0\n1 1 0\n2 1 0\n2 0\n0 0 1\n1 1 2\n"), Limits{});
  EXPECT_EQ(f.segments.size(), 1u);
  ASSERT_EQ(f.points.size(), 1u);
  EXPECT_EQ(f.points[0].p, Vec2(1, 0));
}

void expect_error(const ScratchDir& dir, const std::string& name, const std::string& text,
                  const std::string& fragment, int line) {
  const std::string path = write_temp(dir, name, text);
  try {
    read_poly(path, Limits{});
    FAIL() << name << ": accepted";
  } catch (const svg::InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr(fragment)) << name;
    EXPECT_THAT(e.what(), testing::HasSubstr(path + ":" + std::to_string(line))) << name;
  }
}

TEST(PolyInput, MalformedFilesNameTheLine) {
  const ScratchDir dir;
  expect_error(dir, "truncated", "3 2 0 0\n1 0 0\n2 1 0\n", "fewer lines", 1);
  expect_error(dir, "dimension", "3 3 0 0\n1 0 0 0\n", "dimension 3", 1);
  expect_error(dir, "node_file", "0 2 0 0\n1 0\n1 1 2\n", "separate .node", 1);
  expect_error(dir, "word", "2 2 0 0\n1 0 zero\n2 1 0\n0\n", "expected a number", 2);
  expect_error(dir, "infinite", "2 2 0 0\n1 0 1e999\n2 1 0\n0\n", "not a finite", 2);
  expect_error(dir, "nan", "2 2 0 0\n1 0 nan\n2 1 0\n0\n", "not a finite", 2);
  expect_error(dir, "range", "2 2 0 0\n1 0 0\n2 1 0\n1 0\n1 1 3\n", "out of range", 5);
  expect_error(dir, "negative", "2 2 0 0\n1 0 0\n2 1 0\n-1 0\n", "negative", 4);
  expect_error(dir, "huge", "2000000000 2 0 0\n1 0 0\n", "fewer lines", 1);
  expect_error(dir, "sequence", "2 2 0 0\n1 0 0\n5 1 0\n0\n", "out of sequence", 3);
  expect_error(dir, "no_segments", "2 2 0 0\n1 0 0\n2 1 0\n", "file ends", 3);
  EXPECT_THROW(read_poly("/nonexistent/x.poly", Limits{}), svg::InputError);
}

TEST(PolyInput, LimitsOnTheFileAndItsSegments) {
  const ScratchDir dir;
  const std::string square = "4 2 0 0\n0 0 0\n1 1 0\n2 1 1\n3 0 1\n4 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n0\n";
  Limits limits;
  limits.max_curves = 4;
  EXPECT_EQ(read_poly(write_temp(dir, "four", square), limits).segments.size(), 4u);
  limits.max_curves = 3;
  try {
    read_poly(write_temp(dir, "four", square), limits);
    ADD_FAILURE() << "four segments read with --max-curves 3";
  } catch (const svg::InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("more than 3 segments (--max-curves raises the limit)"));
  }
  limits = Limits{};
  limits.max_input_mb = double(square.size() - 1) / 1048576;  // one byte short
  try {
    read_poly(write_temp(dir, "four", square), limits);
    ADD_FAILURE() << "a file above --max-input-mb read";
  } catch (const svg::InputError& e) {
    const std::string path = dir / "four.poly";
    EXPECT_THAT(e.what(), testing::StartsWith(path + ": the file is larger"));
    EXPECT_THAT(e.what(), testing::Not(testing::HasSubstr(path + ": " + path)));
    EXPECT_THAT(e.what(), testing::HasSubstr("--max-input-mb"));
  }
  EXPECT_THROW(read_poly("/dev/zero", Limits{}), svg::InputError);
}

}  // namespace
}  // namespace curvemesh::features
