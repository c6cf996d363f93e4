#!/usr/bin/python3
"""The depth-averaged model against the finest MPM run of each reference
scene (docs/dam.md, "DAM against the finest MPM"): from two history.csv
files, the runout at the MPM run's end, when each comes to rest, the peak
toe velocity and when, and the onset of the rear's motion.

    dam_against_reference.py LABEL MPM_HISTORY DAM_HISTORY [LABEL MPM DAM ...]

prints one markdown row per method and scene. Rest is the first row from
which the toe moves less than 0.1 m to the end of the history, at least
2 s later (none where the run ends still moving); the rear's onset is the first time it has
moved 0.5 m from where it started.
"""
import csv
import sys

REST_TOLERANCE, REST_SPAN, REAR_ONSET = 0.1, 2.0, 0.5


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in ("time", "runout", "toe_velocity", "rear")}


def value_at(h, key, t):
    """h[key] at time t, linearly between rows; the last value past the end."""
    time = h["time"]
    if t >= time[-1]:
        return h[key][-1]
    k = next(i for i in range(len(time)) if time[i] >= t)
    if k == 0:
        return h[key][0]
    f = (t - time[k - 1]) / (time[k] - time[k - 1])
    return h[key][k - 1] + f * (h[key][k] - h[key][k - 1])


def metrics(h, t_end):
    runout = h["runout"]
    rest = None
    for k in range(len(runout)):
        if h["time"][-1] - h["time"][k] < REST_SPAN:
            break
        if max(runout[k:]) - min(runout[k:]) < REST_TOLERANCE:
            rest = h["time"][k]
            break
    peak = max(range(len(runout)), key=lambda k: h["toe_velocity"][k])
    onset = next((h["time"][k] for k in range(len(runout))
                  if abs(h["rear"][k] - h["rear"][0]) >= REAR_ONSET), None)
    return {
        "runout": value_at(h, "runout", t_end), "rest": rest, "end": h["time"][-1],
        "peak": h["toe_velocity"][peak], "peak_t": h["time"][peak], "onset": onset,
    }


def cell(value, fmt="%.1f"):
    return "-" if value is None else fmt % value


def main(args):
    if len(args) % 3 != 0 or not args:
        sys.exit(__doc__)
    print("| scene | method | runout [m] (at s) | at rest [s] | peak toe velocity [m/s] (at s) "
          "| rear moves from [s] |")
    print("| --- | --- | --- | --- | --- | --- |")
    for k in range(0, len(args), 3):
        label, mpm, dam = args[k:k + 3]
        m_hist, d_hist = read(mpm), read(dam)
        t_end = m_hist["time"][-1]
        for method, h in (("MPM", m_hist), ("DAM", d_hist)):
            m = metrics(h, t_end)
            print(f"| {label} | {method} | {m['runout']:.1f} ({t_end:.1f}) | "
                  f"{cell(m['rest']) if m['rest'] is not None else 'moving at %.0f' % m['end']} | "
                  f"{m['peak']:.2f} ({m['peak_t']:.1f}) | {cell(m['onset'])} |")


if __name__ == "__main__":
    main(sys.argv[1:])
