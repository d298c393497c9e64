#!/usr/bin/env python3
"""`srp experiment objects` and `srp perceive` give the same detections on one demo.

    same_detections.py SRP_EXE EXPERIMENT_OUT

Reads the perception study's cache of the run in EXPERIMENT_OUT (perception/*seed-*.json: the
rawlog it perceived and, per frame and object, the module's pose, confidence and detection flag),
runs `srp perceive --json` on that rawlog with the plan and glove the study used (parts moving,
containers static; the ground truth's tag), and compares object by object, frame by frame.
Exit 0 and "same detections: F frames x N objects" when every sample agrees.
"""
import glob
import json
import subprocess
import sys

POSE_TOL_M = 1e-9        # the same code on the same frames: equal up to JSON's printed digits
QUATERNION_TOL = 1e-9
CONFIDENCE_TOL = 1e-9

srp, out = sys.argv[1], sys.argv[2]
caches = sorted(glob.glob(out + "/perception/*seed-*.json"))
if not caches:
    sys.exit(f"no perception cache under {out}/perception: did `srp experiment objects` run?")
study = json.load(open(caches[0]))
rawlog = study["rawlog"]
gt = json.load(open(rawlog[: -len(".rawlog")] + ".gt.json"))
moving = [n for n, s in study["static"].items() if not s]
static = [n for n, s in study["static"].items() if s]
# the study's plan order: parts then containers, each in ground-truth order
order = [o["class"] for o in gt["objects"]]
moving.sort(key=order.index)
static.sort(key=order.index)
cmd = [srp, "perceive", "--demo", rawlog, "--objects", ",".join(moving), "--static", ",".join(static), "--json",
       "--tag-size", repr(gt["hand"]["tag_size_m"]), "--tag-id", str(gt["hand"]["tag_id"])]
perceived = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)

frames = study["frames"]
if perceived["frames"] != frames:
    sys.exit(f"srp perceive saw {perceived['frames']} frames, the study {frames}")
problems = 0
for obj in perceived["objects"]:
    name = obj["name"]
    for s in obj["samples"]:
        f = s["frame"]
        mine = [o for o in study["refined"][f] if o["class"] == name]
        if len(mine) != 1:
            print(f"frame {f} {name}: the study has {len(mine)} samples, srp perceive 1")
            problems += 1
            continue
        m = mine[0]
        dt = max(abs(a - b) for a, b in zip(m["X_camera_object"]["translation"], s["translation"]))
        dq = max(abs(a - b) for a, b in zip(m["X_camera_object"]["quaternion"], s["quaternion"]))
        if m["detected"] != s["detected"] or dt > POSE_TOL_M or dq > QUATERNION_TOL or \
                abs(m["confidence"] - s["confidence"]) > CONFIDENCE_TOL:
            print(f"frame {f} {name}: study detected={m['detected']} conf={m['confidence']:.6f}, srp perceive "
                  f"detected={s['detected']} conf={s['confidence']:.6f}; position {dt:.3g} m, quaternion {dq:.3g} apart")
            problems += 1
counted = sum(len(f) for f in study["refined"])
samples = sum(len(o["samples"]) for o in perceived["objects"])
if samples != counted:
    print(f"srp perceive gave {samples} samples, the study {counted}")
    problems += 1
if problems:
    sys.exit(f"{problems} samples differ between `srp experiment objects` and `srp perceive`")
print(f"same detections: {frames} frames x {len(perceived['objects'])} objects "
      f"({sum(s['detected'] for o in perceived['objects'] for s in o['samples'])} detected samples)")
