// Runs killed (SIGKILL) at random moments, five times with a fixed seed:
// whatever the moment, the .pvd index lists only frames that exist and are
// whole (ParaView's vtkPVDReader reads the index, VTK's XML reader every
// listed frame, with no error and every particle), and `runout resume`
// finishes the run to the same history and frames, byte for byte, as an
// uninterrupted run with the same thread count. Every other round the
// resume itself is killed once more before the last one.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <vtkCommand.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPVDReader.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <chrono>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"
#include "run_folder.hpp"
#include "runout/output/checkpoint.hpp"

using namespace runout;
using namespace runout::run_folder;

namespace {

// Counts the errors and warnings a VTK object reports.
class ErrorCounter : public vtkCommand {
 public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void*) override { ++count; }
  int count = 0;
};

// The small scene to t = 2 s, a frame every 0.05 s: 512 particles, about
// 800 steps, a second or two here. Checkpoints every 0.15 s, so that a run
// usually holds a frame written after its last checkpoint when it dies.
std::string kill_scene() {
  std::string s = runout::cli_runner::kSmallScene;
  s.replace(s.find("end = 0.2"), 9, "end = 2.0");
  s.replace(s.find("output_interval = 0.1"), 21, "output_interval = 0.05");
  return s;
}

const char* cli() {
  const char* path = std::getenv("RUNOUT_CLI");
  EXPECT_NE(path, nullptr) << "RUNOUT_CLI is set by ctest";
  return path;
}

// Starts runout with args, its output thrown away; the child's pid.
pid_t start(const std::vector<std::string>& args) {
  std::vector<char*> argv{const_cast<char*>(cli())};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

// Kills the child after `seconds` unless it ended first; its exit code, or
// -1 when killed.
int kill_after(pid_t pid, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return WEXITSTATUS(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int run_to_end(const std::vector<std::string>& args) { return kill_after(start(args), 600.0); }

// What a killed run left is readable: every frame the index lists exists,
// reads with no error and holds every particle.
void expect_readable_index(const fs::path& dir, int particles) {
  const fs::path pvd = dir / "small.pvd";
  if (!fs::exists(pvd)) return;  // killed before the first frame
  const std::vector<std::string> files = pvd_files(pvd);
  vtkNew<vtkPVDReader> index;
  vtkNew<ErrorCounter> index_errors;
  index->AddObserver(vtkCommand::ErrorEvent, index_errors);
  index->SetFileName(pvd.c_str());
  index->UpdateInformation();
  EXPECT_EQ(index_errors->count, 0);
  vtkInformation* info = index->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  EXPECT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()),
            static_cast<int>(files.size()));
  for (const std::string& f : files) {
    ASSERT_TRUE(fs::exists(dir / f)) << f << " is listed but missing";
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    vtkNew<ErrorCounter> errors;
    reader->AddObserver(vtkCommand::ErrorEvent, errors);
    reader->AddObserver(vtkCommand::WarningEvent, errors);
    reader->SetFileName((dir / f).c_str());
    reader->Update();
    EXPECT_EQ(errors->count, 0) << f;
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), particles) << f;
  }
}

}  // namespace

TEST(KillResume, KilledRunsResumeToTheUninterruptedResult) {
  ScratchFolder folder;
  const std::string scene = folder.write("kill.toml", kill_scene());
  const std::vector<std::string> common{"-q", "-t", "2"};
  const auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), common.begin(), common.end());
    return args;
  };

  const fs::path reference = folder.path() / "reference";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run_to_end(with({"run", scene, "--cell", "0.25", "-o", reference.string()})), 0);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vtkNew<vtkXMLUnstructuredGridReader> first;
  first->SetFileName((reference / "frame_00000.vtu").c_str());
  first->Update();
  const int particles = static_cast<int>(first->GetOutput()->GetNumberOfPoints());
  ASSERT_EQ(particles, 512);

  std::mt19937 rng(20240607);
  std::uniform_real_distribution<double> moment(0.1, 0.95);
  for (int round = 0; round < 5; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const fs::path out = folder.path() / ("killed" + std::to_string(round));
    const double at = moment(rng) * wall;
    kill_after(start(with({"run", scene, "--cell", "0.25", "-o", out.string(), "--checkpoint-every", "0.15"})), at);
    expect_readable_index(out, particles);
    const bool has_checkpoint = fs::exists(out / "checkpoint.bin");
    const std::size_t listed = fs::exists(out / "small.pvd") ? pvd_files(out / "small.pvd").size() : 0;
    std::printf("round %d: killed at %.2f s of %.2f s with %zu frames listed; checkpoint: %s\n",
                round, at, wall, listed,
                has_checkpoint
                    ? (std::to_string(read_checkpoint((out / "checkpoint.bin").string())
                                          .state.schedule.frames) + " frames")
                          .c_str()
                    : "none yet");
    if (!has_checkpoint) {
      // Killed before the first checkpoint: nothing to resume, and resume says so.
      EXPECT_EQ(run_to_end(with({"resume", out.string()})), 66);
      continue;
    }
    if (round % 2 == 1) {
      kill_after(start(with({"resume", out.string()})), moment(rng) * 0.5 * wall);
      expect_readable_index(out, particles);
    }
    ASSERT_EQ(run_to_end(with({"resume", out.string()})), 0);
    expect_frames_in_sequence(out, out / "small.pvd");
    expect_same_run(reference, out, "small.pvd");
  }
}
