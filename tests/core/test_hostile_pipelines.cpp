// Pipeline files written carelessly or with intent: duplicate keys, anchors
// under --set, names that would lead the output elsewhere, cycles on
// oneself, folders and FIFOs, deep nesting, NUL bytes, files that are not
// pipelines. Each is an error with what and where, never a crash or a hang.
#include <sys/stat.h>

#include "pipeline_fixture.hpp"

using namespace touchcloud;
using touchcloud::test::mentions;
namespace fs = std::filesystem;

namespace {
const std::string kRead = "  - id: read\n    plugin: cloud_reader\n    params: {path: " + touchcloud::test::gel_dome_cloud() + "}\n";
}  // namespace

class HostilePipelines : public touchcloud::test::PipelineFixture {
 protected:
  std::string load_error(const fs::path& file) {
    try {
      Pipeline::load(file, {}, registry_);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(loaded)";
  }
};

TEST_F(HostilePipelines, DuplicateKeysAreAnErrorWithBothPositions) {
  const auto d = errors("pipeline: t\nstages:\n  - id: a\n    plugin: test_counter\n    plugin: downsample\n"
                        "    params: {step: 1}\n    params: {step: 2}\n");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_TRUE(mentions(d[0], "duplicate key 'plugin' (first at " + (dir_ / "p.yaml").string() + ":4:5)")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 5);
  EXPECT_TRUE(mentions(d[1], "duplicate key 'params' (first at " + (dir_ / "p.yaml").string() + ":6:5)")) << d[1].str();
  EXPECT_EQ(d[1].where.line, 7);
}

// --set changes the stage it names, not the stages sharing its YAML anchor.
TEST_F(HostilePipelines, AnOverrideChangesOnlyItsStageThroughAnAnchor) {
  Pipeline p = load("pipeline: t\nstages:\n"
                    "  - id: a\n    plugin: test_counter\n    params: {offsets: &o [1, 2], step: &s 3}\n"
                    "  - id: b\n    plugin: test_counter\n    params: {offsets: *o, step: *s}\n",
                    {{"a.offsets", "[5, 6]"}, {"a.step", "4"}});
  const auto params = p.parameters();
  EXPECT_EQ(std::get<std::vector<double>>(params.at("a").at("offsets")), (std::vector<double>{5, 6}));
  EXPECT_EQ(std::get<std::vector<double>>(params.at("b").at("offsets")), (std::vector<double>{1, 2}));
  EXPECT_EQ(std::get<double>(params.at("a").at("step")), 4.0);
  EXPECT_EQ(std::get<double>(params.at("b").at("step")), 3.0);
}

TEST_F(HostilePipelines, ThePipelineNameIsAnIdentifier) {
  for (const std::string name : {"/tmp/x", "..", "../..", "a/b"}) {
    const auto d = errors("pipeline: '" + name + "'\nstages:\n  - id: a\n    plugin: test_counter\n");
    ASSERT_EQ(d.size(), 1u) << name;
    EXPECT_TRUE(mentions(d[0], "'pipeline' is the pipeline's name, an identifier")) << d[0].str();
    EXPECT_EQ(d[0].where.line, 1);
  }
}

TEST_F(HostilePipelines, AStageReadingItsOwnOutputIsACycleWithItsPosition) {
  const auto d = errors("pipeline: t\nstages:\n  - id: a\n    plugin: test_counter\n    inputs: {previous: a.value}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "the inputs form a cycle: a -> a")) << d[0].str();
  EXPECT_EQ(d[0].where.line, 5);
}

TEST_F(HostilePipelines, AWriterPathOutsideTheOutputFolderIsRefusedAtLoadAndDotDotNamesAreNot) {
  const std::string writer = "  - id: w\n    plugin: cloud_writer\n    inputs: {cloud: read.cloud}\n    params: {path: ";
  for (const std::string path : {"../x.ply", "/tmp/x.ply", "a/../../x.ply"}) {
    const auto d = errors("pipeline: t\nstages:\n" + kRead + writer + path + "}\n");
    ASSERT_EQ(d.size(), 1u) << path;
    EXPECT_TRUE(mentions(d[0], "must stay inside the output folder")) << d[0].str();
    EXPECT_EQ(d[0].where.line, 9);
  }
  // A name that merely starts with two dots is a file like any other.
  EXPECT_NO_THROW(load("pipeline: t\nstages:\n" + kRead + writer + "..hidden.ply}\n"));
  EXPECT_NO_THROW(load("pipeline: t\nstages:\n" + kRead + writer + "sub/../x.ply}\n"));
}


// A later run into the same folder would remove a file in a staging folder.
TEST_F(HostilePipelines, AWriterPathInAStagingFolderIsRefusedAtLoad) {
  const std::string writer = "  - id: w\n    plugin: cloud_writer\n    inputs: {cloud: read.cloud}\n    params: {path: ";
  for (const std::string path : {".touchcloud-staging-7/kept.ply", "./.touchcloud-staging-x/a/b.ply",
                                 "sub/../.touchcloud-staging-1/x.ply"}) {
    const auto d = errors("pipeline: t\nstages:\n" + kRead + writer + path + "}\n");
    ASSERT_EQ(d.size(), 1u) << path;
    EXPECT_TRUE(mentions(d[0], "which the toolkit reserves for its staging folders")) << d[0].str();
    EXPECT_EQ(d[0].where.line, 9);
  }
  EXPECT_NO_THROW(load("pipeline: t\nstages:\n" + kRead + writer + "sub/.touchcloud-staging-1/x.ply}\n"));
}
TEST_F(HostilePipelines, AFolderOrAFifoAsThePipelineIsBadInputWithoutBlocking) {
  fs::create_directory(dir_ / "folder.yaml");
  EXPECT_NE(load_error(dir_ / "folder.yaml").find("is a folder, not a file"), std::string::npos);
  ASSERT_EQ(::mkfifo((dir_ / "fifo.yaml").c_str(), 0600), 0);
  EXPECT_NE(load_error(dir_ / "fifo.yaml").find("is not a regular file"), std::string::npos);
}

TEST_F(HostilePipelines, AFifoAsAnInputFileIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo.pcd").c_str(), 0600), 0);
  const auto d = errors("pipeline: t\nstages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: fifo.pcd}\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "is not a regular file")) << d[0].str();
}

TEST_F(HostilePipelines, DeepNestingSaysSo) {
  const std::string deep = "pipeline: t\nstages: " + std::string(5000, '[') + std::string(5000, ']') + "\n";
  const auto d = errors(deep);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(mentions(d[0], "nested too deeply")) << d[0].str();
}

TEST_F(HostilePipelines, ANulByteInANameDoesNotCutTheMessage) {
  const std::string yaml = std::string("pipeline: t\nstages:\n  - id: \"a\\0b\"\n    plugin: test_counter\n");
  try {
    load(yaml);
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("stage id 'a\\x00b' is not an identifier"), std::string::npos) << what;
  }
}

TEST_F(HostilePipelines, AFileThatIsNotAPipelineIsNotQuotedBack) {
  const std::string secret = "root:$y$j9T$0123456789abcdefghijklmnopqrstuvwxyzABCDEF:19000:0:99999:7:::";
  const auto d = errors(secret + ": x\nother: y\n");
  ASSERT_FALSE(d.empty());
  for (const auto& diag : d) EXPECT_EQ(diag.message.find("ABCDEF"), std::string::npos) << diag.message;
}

TEST_F(HostilePipelines, AnAliasedStageIsRefusedNotRepeated) {
  const auto d = errors("pipeline: t\nstages: &s\n  - id: a\n    loop:\n      max_iterations: 2\n      stages: *s\n");
  ASSERT_FALSE(d.empty());
  EXPECT_TRUE(mentions(d[0], "appears a second time (a YAML alias)")) << d[0].str();
}
