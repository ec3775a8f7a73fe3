"""Checks of grain-demlab's reading of DEMLab projects: every shipped project is accepted, and bad
input is refused before anything runs, with a message naming the file, the key (or the line of the
model-parts file) and the valid values.

Usage: front_end_test.py GRAIN_DEMLAB DEMLAB_PROJECTS_FOLDER
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

tool, projects = sys.argv[1], sys.argv[2]
failures = 0


def check(name, ok, detail=""):
    global failures
    print("%s %s%s" % ("ok  " if ok else "FAIL", name, (": " + detail) if detail and not ok else ""))
    failures += 0 if ok else 1


def run(path):
    r = subprocess.run([sys.executable, tool, path, "--check"], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    return r.returncode, r.stdout + r.stderr


# every project DEMLab ships is accepted
shipped = sorted(glob.glob(os.path.join(projects, "*", "*", "ProjectParameters.json")))
check("23 projects found", len(shipped) == 23, str(len(shipped)))
for p in shipped:
    code, out = run(p)
    check("accepted: " + os.path.relpath(p, projects), code == 0 and "is valid" in out, out[-400:])

base = os.path.join(projects, "mechanical", "bounce_straight")
work = tempfile.mkdtemp(prefix="grain_demlab_front_end_")


def mutated(label, change_json=None, model_parts=None, raw_json=None, source=base):
    """A copy of a project (bounce_straight by default) with one change; returns (status,
    output, project path)."""
    folder = os.path.join(work, label)
    shutil.copytree(source, folder)
    path = os.path.join(folder, "ProjectParameters.json")
    if raw_json is not None:
        with open(path, "w") as f:
            f.write(raw_json)
    elif change_json is not None:
        with open(path) as f:
            d = json.load(f)
        change_json(d)
        with open(path, "w") as f:
            json.dump(d, f, indent=1)
    if model_parts is not None:
        with open(os.path.join(folder, "ModelParts.txt"), "w") as f:
            f.write(model_parts)
    code, out = run(path)
    return code, out, path


def refused(label, needles, **kw):
    code, out, path = mutated(label, **kw)
    missing = [n for n in needles if n not in out]
    check("refused: " + label, code == 1 and not missing and "Traceback" not in out,
          "status %d, missing %s in: %s" % (code, missing, out.strip()[-500:]))


refused("unknown key", ["ProjectParameters.json", "Solver.time_stepp", "valid keys here",
                        "final_time"],
        change_json=lambda d: d["Solver"].update(time_stepp=1e-4))
refused("unknown section", ["'Solvers'", "valid keys here", "InteractionModel"],
        change_json=lambda d: d.update(Solvers={}))
refused("bad normal model", ["InteractionModel.contact_force_normal.model", "'linear'",
                             "viscoelastic_linear, viscoelastic_nonlinear, elastoplastic_linear"],
        change_json=lambda d: d["InteractionModel"]["contact_force_normal"].update(model="linear"))
refused("restitution out of range", ["restitution_coeff", "1.5", "(0, 1]"],
        change_json=lambda d: d["InteractionModel"]["contact_force_normal"].update(
            restitution_coeff=1.5))
refused("negative time step", ["Solver.time_step", "-0.0001", "(0, inf)"],
        change_json=lambda d: d["Solver"].update(time_step=-1e-4))
refused("missing final time", ["Solver.final_time", "required"],
        change_json=lambda d: d["Solver"].pop("final_time"))
refused("missing density", ["Material[0].density", "required in a mechanical analysis"],
        change_json=lambda d: d["Material"].pop("density"))
refused("unknown model part", ["model_parts", "'TOP'", "valid names: PARTICLES, WALLS"],
        change_json=lambda d: d["Material"].update(model_parts=["PARTICLES", "TOP"]))
refused("graph axis", ["Graph[0].axis_y", "'height'", "coordinate_y"],
        change_json=lambda d: d["Graph"][0].update(axis_y="height"))
refused("graph of a missing particle", ["there is no particle 7"],
        change_json=lambda d: d["Graph"][0]["curve"].update(particle_y=7))
refused("spline table", ["interpolation", "'spline'", "valid values: linear"],
        change_json=lambda d: d.update(PrescribedCondition={"force": {
            "type": "table", "values": [[0, 0, 0], [1, 1, 1]], "interpolation": "spline",
            "model_parts": ["PARTICLES"]}}))
refused("unsorted table", ["values", "the times must increase", "row 2"],
        change_json=lambda d: d.update(PrescribedCondition={"force": {
            "type": "table", "values": [[1, 0, 0], [0, 1, 1]], "model_parts": ["PARTICLES"]}}))
refused("oscillation without period", ["PrescribedCondition.torque", "period", "required"],
        change_json=lambda d: d.update(PrescribedCondition={"torque": {
            "type": "oscillatory", "base_value": 0, "amplitude": 1,
            "model_parts": ["PARTICLES"]}}))
refused("invalid JSON", ["ProjectParameters.json:3", "not valid JSON"],
        raw_json='{\n "ProblemData": {\n "name" "x"\n }\n}\n')
refused("negative radius", ["ModelParts.txt:3", "radius", "-0.5", "valid range (0, inf)"],
        model_parts="%PARTICLES.SPHERE\n1\n1 0.0 2.0 0.0 -0.5\n\n%WALLS.LINE\n1\n"
                    "1 -1.5 0.0 1.5 0.0\n")
refused("not a number", ["ModelParts.txt:3", "'2.O' is not a number"],
        model_parts="%PARTICLES.SPHERE\n1\n1 0.0 2.O 0.0 0.5\n")
refused("short line", ["ModelParts.txt:3", "expected 5 values, got 4"],
        model_parts="%PARTICLES.SPHERE\n1\n1 0.0 2.0 0.5\n")
refused("unknown block", ["ModelParts.txt:1", "'%PARTICLE.SPHERE'", "%PARTICLES.SPHERE"],
        model_parts="%PARTICLE.SPHERE\n1\n1 0.0 2.0 0.0 0.5\n")
refused("id used twice", ["ModelParts.txt:4", "particle id 1 is used twice (first on line 3)"],
        model_parts="%PARTICLES.SPHERE\n2\n1 0.0 2.0 0.0 0.5\n1 3.0 2.0 0.0 0.5\n")
refused("ids with a gap", ["particle ids must be 1..N", "missing: [2]"],
        model_parts="%PARTICLES.SPHERE\n2\n1 0.0 2.0 0.0 0.5\n3 3.0 2.0 0.0 0.5\n")
refused("model part of a missing wall", ["%MODELPART floor", "there is no wall 4"],
        model_parts="%PARTICLES.SPHERE\n1\n1 0.0 2.0 0.0 0.5\n%MODELPART\nNAME floor\n"
                    "WALLS 1\n4\n")
refused("degenerate wall", ["ModelParts.txt:7", "two equal end points"],
        model_parts="%PARTICLES.SPHERE\n1\n1 0.0 2.0 0.0 0.5\n\n%WALLS.LINE\n1\n"
                    "1 0.0 0.0 0.0 0.0\n")
resting = os.path.join(projects, "thermal", "resting_multiple")
refused("Tsuji damping with a coefficient", ["damping_coeff", "damping_formula TTI",
                                             "restitution_coeff"],
        change_json=lambda d: d["InteractionModel"].update(contact_force_normal={
            "model": "viscoelastic_nonlinear", "damping_coeff": 3.0}))
refused("dashpot without damping", ["contact_force_tangent.damping_coeff", "(0, inf)"],
        change_json=lambda d: d["InteractionModel"].update(contact_force_tangent={
            "model": "simple_dashpot", "damping_coeff": 0.0}))
refused("no outputs", ["Output.number_output", "[1, inf)"],
        change_json=lambda d: d["Output"].update(number_output=0))
refused("negative temperature", ["InitialCondition.temperature", "valid range [0, inf)"],
        source=resting,
        change_json=lambda d: d["InitialCondition"]["temperature"][0].update(value=-10.0))
refused("convection on some particles", ["ConvectionModel", "particles without one: [2, 3"],
        source=resting,
        change_json=lambda d: d["ConvectionModel"].update(model_parts=[], particles=[1]))
refused("incomplete fluid", ["viscosity", "required by the convection model"], source=resting,
        change_json=lambda d: d["Material"][1].pop("viscosity"))
refused("thermal graph in a mechanical analysis", ["Graph 'Vertical Position'", "temperature",
                                                    "mechanical analysis"],
        change_json=lambda d: d["Graph"][0].update(axis_y="temperature"))
refused("table file not a name", ["file", "expected a non-empty string"],
        change_json=lambda d: d.update(PrescribedCondition={"force": {
            "type": "table", "file": 3, "model_parts": ["PARTICLES"]}}))
refused("flat polygon", ["BoundingBox.points_x", "no area"],
        change_json=lambda d: d.update(BoundingBox={"shape": "polygon", "points_x": [0, 1, 2],
                                                    "points_y": [0, 1, 2]}))
code, out, _ = mutated("open bounding box", change_json=lambda d: d.update(
    BoundingBox={"shape": "rectangle", "limit_min": [-5.0, -1.0]}))
check("accepted: a rectangle bounding box with one limit (the other open)", code == 0, out[-300:])
code, out, _ = mutated("prescribed force through a model part with walls", change_json=lambda d:
                       d.update(PrescribedCondition={"force": {"type": "constant",
                                                               "value": [1.0, 0.0],
                                                               "model_parts": ["all"]}}),
                       model_parts="%PARTICLES.SPHERE\n1\n1 0.0 2.0 0.0 0.5\n%WALLS.LINE\n1\n"
                                   "1 -1.5 0.0 1.5 0.0\n%MODELPART\nNAME all\nPARTICLES 1\n1\n"
                                   "WALLS 1\n1\n")
check("accepted: a prescribed force through a model part that holds walls (on its particles)",
      code == 0, out[-300:])
shutil.rmtree(work, ignore_errors=True)
print("%d failure%s" % (failures, "" if failures == 1 else "s"))
sys.exit(1 if failures else 0)
