#!/usr/bin/env python3
"""Reads exported ROS 2 trajectories the way `ros2 topic pub --yaml-file` does
(PyYAML, yaml.load_all: every document of the file) and compares each with a
reference export of the same trajectory.

usage: read_exports.py REFERENCE.yaml FILE.yaml...

Prints one JSON object: files read, files holding exactly one document, files
whose document equals the reference's (joint_names and header.frame_id compared
only for type and count: the hostile-name cases change them on purpose), and the names of
the files that failed with the reason.
"""
import json
import sys

import yaml


# libyaml's loader when PyYAML has it (the same YAML 1.1 scanner, in C: the 2400
# files of the sweep in seconds); every 10th file is also read by PyYAML's own
# pure-Python loader, and both must agree.
FAST = getattr(yaml, "CFullLoader", yaml.FullLoader)


def documents(path, loader=FAST):
    with open(path, "rb") as f:
        return list(yaml.load_all(f, Loader=loader))


def without_names(doc):
    """The document without its names (joint_names, header.frame_id), and the names."""
    if isinstance(doc, dict):
        doc = dict(doc)
        names = doc.pop("joint_names", None)
        frame_id = None
        if isinstance(doc.get("header"), dict):
            doc["header"] = dict(doc["header"])
            frame_id = doc["header"].pop("frame_id", None)
        return doc, (names, frame_id)
    return doc, (None, None)


def main():
    reference, _ = without_names(documents(sys.argv[1])[0])
    result = {"files": 0, "one_document": 0, "equal_data": 0, "failures": []}
    for i, path in enumerate(sys.argv[2:]):
        result["files"] += 1
        try:
            docs = documents(path)
            if i % 10 == 0 and documents(path, yaml.FullLoader) != docs:
                result["failures"].append({"file": path, "reason": "the C and the Python loader disagree"})
                continue
        except Exception as e:  # a file PyYAML cannot read is a failure too
            result["failures"].append({"file": path, "reason": "unreadable: " + str(e)[:200]})
            continue
        if len(docs) != 1:
            result["failures"].append({"file": path, "reason": "%d documents" % len(docs)})
            continue
        result["one_document"] += 1
        data, names = without_names(docs[0])
        if data != reference:
            result["failures"].append({"file": path, "reason": "data differs from the reference"})
            continue
        joint_names, frame_id = names
        if not (isinstance(joint_names, list) and len(joint_names) == 6 and all(isinstance(n, str) for n in joint_names)
                and isinstance(frame_id, str)):
            result["failures"].append({"file": path, "reason": "joint_names is not a list of 6 strings or "
                                                               "header.frame_id not a string"})
            continue
        result["equal_data"] += 1
    result["failures"] = result["failures"][:10]
    print(json.dumps(result))


if __name__ == "__main__":
    main()
