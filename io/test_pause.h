#pragma once
// A test hook that makes races deterministic: a process reaching a named point pauses there while a file exists.
// With SACFUSE_TEST_PAUSE="<point>=<file>" (several separated by ','), PauseAtTestPoint("<point>") creates <file>
// (holding the pid) and waits until someone deletes it (polling every 10 ms, at most 120 s), then goes on. The
// end-to-end tests start a process paused at a point, act while it waits (a second run, an edited input...), then
// delete the file. Without the variable it costs one getenv.
namespace sacfuse {

void PauseAtTestPoint(const char* point);

}  // namespace sacfuse
