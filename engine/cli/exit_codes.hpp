#pragma once
// runout's exit codes, for every command: sysexits(3) where one fits.
// Each command's header says which of them it gives and when.

namespace runout::cli {

enum Exit {
  kOk = 0,             // done: the run reached its end, the file is written
  kUsage = 64,         // the command line is wrong (CLI11's errors too)
  kSceneInvalid = 65,  // the scene (or a checkpoint, a frame) is invalid or corrupt
  kNoScene = 66,       // the scene file, checkpoint or output index cannot be read
  kUnavailable = 69,   // the backend (or sbatch) asked for cannot run here
  kBlowUp = 70,        // the run blew up or a study's run failed; frames before are kept
  kCantCreate = 73,    // the output cannot be written
  kFolderBusy = 75,    // EX_TEMPFAIL: another runout writes into the folder; try when it is done
  kResumeRefused = 79, // past sysexits' range: the folder does not go with its checkpoint
  kSignalBase = 128    // stopped by a signal: 128 + its number (130, 143, 129), as a shell says
};

}  // namespace runout::cli
