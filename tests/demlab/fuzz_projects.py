"""Fuzzer of grain-demlab's reading of DEMLab projects: DEMLab's own projects with random
changes (keys removed or added, values replaced by numbers, NaN, infinities, strings, lists,
objects, booleans and null; model-parts lines replaced, cut, doubled or garbled) are read, checked
and turned into a run file and a program (`--check`'s work, nothing built). Each must be accepted
or refused with grain_demlab's ProjectError (file, key or line, valid values); any other
exception fails. A run file that is written must hold only finite numbers where numbers are
expected and ids the model-parts file has.

The process may use 2 GB of memory at most: a reader that allocates without bound fails.

Usage: fuzz_projects.py BUILD_PYTHON_FOLDER DEMLAB_PROJECTS SECONDS [SEED]
Prints PASSED or FAILED with the input that failed.
"""
import copy
import glob
import json
import math
import os
import random
import shutil
import sys
import tempfile
import time
import traceback

# a reader that allocates without bound fails as a MemoryError, not as a killed process
import resource  # noqa: E402
resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
sys.path.insert(0, sys.argv[1])
from grain import demlab  # noqa: E402

projects_root, seconds = sys.argv[2], float(sys.argv[3])
rng = random.Random(int(sys.argv[4]) if len(sys.argv) > 4 else 1)
projects = sorted(glob.glob(os.path.join(projects_root, "*", "*", "ProjectParameters.json")))
# the large packs make slow cases and add nothing the small ones do not have
projects = [p for p in projects if os.path.getsize(os.path.join(os.path.dirname(p),
                                                                "ModelParts.txt")) < 20000]
work = tempfile.mkdtemp(prefix="grain_demlab_fuzz_")

WORDS = ["", "x", "PARTICLES", "WALLS", "constant", "linear", "oscillatory", "table", "TTI",
         "energy", "viscoelastic_linear", "sphere_hanz_marshall", "bob", "rectangle", "circle",
         "polygon", "motion", "temperature", "time", "coordinate_x", "solid", "fluid",
         "mp_name", "velocity_y", "a b", "../x", "%PARTICLES.SPHERE"]


def random_value(depth=0):
    r = rng.random()
    if r < 0.25:
        return rng.choice([0, 1, -1, 2, 0.5, -0.5, 1e300, -1e300, 1e-300, 3, 7, 1000, 400.0,
                           float("nan"), float("inf"), float("-inf"), 2 ** 63, 1.5])
    if r < 0.4:
        return rng.choice(WORDS)
    if r < 0.5:
        return rng.choice([True, False, None])
    if r < 0.8 and depth < 2:
        return [random_value(depth + 1) for _ in range(rng.choice([0, 1, 2, 2, 3, 4]))]
    if depth < 2:
        keys = ["value", "type", "model", "particles", "model_parts", "interval", "name",
                "curve", "particle_y", "values", "x"]
        return {rng.choice(keys): random_value(depth + 1) for _ in range(rng.randint(0, 3))}
    return rng.random()


def paths(obj, prefix=()):
    """Every (path, value) of a JSON tree."""
    yield prefix, obj
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from paths(v, prefix + (i,))


def mutate_json(d):
    d = copy.deepcopy(d)
    for _ in range(rng.choice([1, 1, 2, 3])):
        all_paths = [p for p, _ in paths(d) if p]
        if not all_paths:
            break
        p = rng.choice(all_paths)
        parent = d
        for k in p[:-1]:
            parent = parent[k]
        key = p[-1]
        action = rng.random()
        if action < 0.3 and isinstance(parent, dict):
            del parent[key]
        elif action < 0.4 and isinstance(parent, dict):
            parent[rng.choice(WORDS) or "extra"] = random_value()
        elif action < 0.5 and isinstance(parent, list):
            parent.append(copy.deepcopy(parent[key]))
        else:
            parent[key] = random_value()
    return d


def mutate_lines(text):
    lines = text.split("\n")
    for _ in range(rng.choice([1, 1, 2, 4])):
        if not lines:
            break
        k = rng.randrange(len(lines))
        action = rng.random()
        if action < 0.25:
            del lines[k]
        elif action < 0.4:
            lines.insert(k, lines[k])
        elif action < 0.7:
            words = lines[k].split()
            if words:
                words[rng.randrange(len(words))] = str(random_value()) if rng.random() < 0.7 \
                    else rng.choice(["nan", "inf", "-1", "0", "1e400", "x", "%MODELPART"])
            lines[k] = " ".join(words)
        elif action < 0.85:
            lines[k] = lines[k][:rng.randrange(len(lines[k]) + 1)]
        else:
            lines = lines[:k]
    return "\n".join(lines)


def check_run_file(text, project):
    for line in text.splitlines():
        words = line.split()
        if not words or words[0] in ("name", "analysis", "param", "record", "print"):
            continue
        for w in words[1:]:
            try:
                v = float(w)
            except ValueError:
                continue
            if math.isnan(v) or (math.isinf(v) and words[0] not in ("bbox", "sink",
                                                                     "condition")):
                raise AssertionError("run file line with %s: %s" % (w, line[:200]))


start = time.time()
cases = accepted = 0
failed = None
while time.time() - start < seconds and failed is None:
    source = rng.choice(projects)
    folder = os.path.join(work, "p")
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(os.path.dirname(source), folder,
                    ignore=shutil.ignore_patterns("*_out", "grain_demlab"))
    path = os.path.join(folder, "ProjectParameters.json")
    with open(source) as f:
        d = json.load(f)
    mp_path = os.path.join(folder, "ModelParts.txt")
    with open(mp_path) as f:
        mp = f.read()
    r = rng.random()
    if r < 0.6:
        d = mutate_json(d)
    elif r < 0.9:
        mp = mutate_lines(mp)
    else:
        d = mutate_json(d)
        mp = mutate_lines(mp)
    if rng.random() < 0.05:
        text = json.dumps(d)
        text = text[:rng.randrange(len(text) + 1)]  # cut JSON
    else:
        text = json.dumps(d)  # NaN and Infinity written as JSON's extensions, as Python reads
    with open(path, "w") as f:
        f.write(text)
    with open(mp_path, "w") as f:
        f.write(mp)
    cases += 1
    try:
        p = demlab.Project(path)
        check_run_file(p.run_file(), p)
        p.program()
        accepted += 1
    except demlab.ProjectError:
        pass
    except Exception:  # anything else is a defect
        failed = (source, text[:3000], mp[:3000], traceback.format_exc())
shutil.rmtree(work, ignore_errors=True)
print("demlab fuzz: %d cases in %.0f s, %d accepted" % (cases, time.time() - start, accepted))
if failed:
    print("FAILED on a change of %s\nJSON: %s\nModelParts: %s\n%s" % failed)
    sys.exit(1)
print("PASSED")
