#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""docs/scene.schema.json against the scene loader, run by ctest (tests/schema/CMakeLists.txt).

  scene_schema_test.py files  --source DIR --probe EXE --cli EXE
      Every sample scene names the schema with "$schema" and validates; every scene file under tests/
      gets the same verdict from the schema and the loader; the scene writer's output for each sample
      (scene_probe resave) and `supermodal fit --scene` output validate.
  scene_schema_test.py agree  --source DIR --probe EXE
      Walks the schema: for every object it knows, builds scenes that set each key to a valid value, to
      each bound of its range and just past it, to each choice, to the wrong type, that leave out a
      key or add a made-up one, and checks that the loader and the schema give each scene the same
      verdict (and the one expected). Plus the rules between keys that the schema states (if/then).
  scene_schema_test.py keys   --source DIR
      The key and choice lists in the loader's source (engine/src/scene/*.cpp: every
      `const std::vector<std::string_view> k_...`) equal the schema's property and enum sets, object by
      object; docs/scene_format.md mentions every schema key; every number's description gives its unit.

Why both `agree` and `keys`: `agree` can only exercise keys the schema knows, so a key the loader
accepts and the schema lacks would pass it; `keys` catches that from the source. `keys` alone would
miss ranges, types and required keys; `agree` catches those from behaviour. Exit status 77 (ctest:
skipped) when python3-jsonschema is missing.
"""

import argparse
import copy
import json
import math
import os
import re
import subprocess
import sys
import tempfile

try:
    import jsonschema
except ImportError:
    print("SKIPPED: python3-jsonschema is not installed (scripts/deps.sh installs it: "
          "apt-get install python3-jsonschema)")
    sys.exit(77)

ANNOTATIONS = ("$schema", "comment")
DEFS = "#/definitions/"

failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def load_schema(source):
    with open(os.path.join(source, "docs", "scene.schema.json"), encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft7Validator.check_schema(schema)
    return schema


def make_validator(schema):
    return jsonschema.Draft7Validator(schema)


def schema_verdict(validator, doc):
    errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
    if not errors:
        return True, ""
    e = errors[0]
    return False, "/" + "/".join(str(p) for p in e.absolute_path) + ": " + e.message[:200]


def loader_verdicts(probe, docs, cwd):
    """The loader's verdict on each document: (accepted, message)."""
    text = "".join(json.dumps(d, allow_nan=False) + "\n" for d in docs)
    run = subprocess.run([probe, "check"], input=text, capture_output=True, text=True, cwd=cwd, check=False)
    lines = run.stdout.splitlines()
    if run.returncode != 0 or len(lines) != len(docs):
        raise SystemExit(f"scene_probe check failed ({run.returncode}): {run.stderr}")
    return [(line == "ok", "" if line == "ok" else line[len("error: "):]) for line in lines]


# ---- files ----------------------------------------------------------------------------------------------


def scene_files(root):
    out = []
    for folder, _, names in os.walk(root):
        out += [os.path.join(folder, n) for n in names if n.endswith(".json")]
    return sorted(out)


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def looks_like_scene(path):
    doc = read_json(path)
    return isinstance(doc, dict) and ("bodies" in doc or "settings" in doc or "include" in doc)


def check_file_verdicts(validator, probe, paths, expect_valid):
    """Schema and loader agree on each file; with expect_valid both must accept it."""
    for path in paths:
        doc = read_json(path)
        ok, why = schema_verdict(validator, doc)
        # Through the probe in the file's folder, so includes and meshes resolve as load_scene would.
        (loaded, message), = loader_verdicts(probe, [doc], os.path.dirname(path))
        name = os.path.relpath(path)
        if ok != loaded:
            fail(f"{name}: the schema {'accepts' if ok else 'refuses (' + why + ')'} but the loader "
                 f"{'accepts' if loaded else 'refuses (' + message + ')'}")
        elif expect_valid and not ok:
            fail(f"{name}: refused by both: schema {why}; loader {message}")


def write_test_mesh(path):
    """An ellipsoid as an OBJ, for `supermodal fit`."""
    rows, cols = 12, 24
    lines = []
    for i in range(rows + 1):
        theta = math.pi * i / rows
        for j in range(cols):
            phi = 2 * math.pi * j / cols
            lines.append(f"v {0.3 * math.sin(theta) * math.cos(phi):.6f} {0.1 * math.cos(theta):.6f} "
                         f"{0.2 * math.sin(theta) * math.sin(phi):.6f}")
    for i in range(rows):
        for j in range(cols):
            a, b = i * cols + j + 1, i * cols + (j + 1) % cols + 1
            c, d = a + cols, b + cols
            lines.append(f"f {a} {c} {d}")
            lines.append(f"f {a} {d} {b}")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def command_files(args):
    schema = load_schema(args.source)
    validator = make_validator(schema)
    schema_path = os.path.join(args.source, "docs", "scene.schema.json")

    # Samples: valid, and they name the schema by a path relative to themselves that leads to it.
    samples = [p for p in scene_files(os.path.join(args.source, "samples")) if looks_like_scene(p)]
    if len(samples) < 6:
        fail(f"expected the sample scenes under samples/, found {len(samples)}")
    for path in samples:
        ref = read_json(path).get("$schema")
        if not isinstance(ref, str) or not os.path.isfile(os.path.join(os.path.dirname(path), ref)) or \
                not os.path.samefile(os.path.join(os.path.dirname(path), ref), schema_path):
            fail(f"{os.path.relpath(path)}: \"$schema\" is {ref!r}, expected a relative path to "
                 "docs/scene.schema.json")
    check_file_verdicts(validator, args.probe, samples, expect_valid=True)

    # Scene files the tests keep (CLI scenes, fuzz corpus and regressions, editor scenes): the schema and
    # the loader agree on each, valid or not.
    kept = [p for p in scene_files(os.path.join(args.source, "tests")) if looks_like_scene(p)]
    check_file_verdicts(validator, args.probe, kept, expect_valid=False)

    with tempfile.TemporaryDirectory(prefix="supermodal_schema_") as tmp:
        # The scene writer (save_scene) on every sample: its output is valid.
        written = []
        for path in samples:
            out = os.path.join(tmp, "resaved_" + os.path.basename(path))
            run = subprocess.run([args.probe, "resave", path, out], capture_output=True, text=True,
                                 check=False)
            if run.returncode != 0:
                fail(f"scene_probe resave {os.path.relpath(path)}: {run.stderr.strip()}")
                continue
            written.append(out)
        # `supermodal fit --scene` (and with --attach, which adds a render mesh).
        mesh = os.path.join(tmp, "ellipsoid.obj")
        write_test_mesh(mesh)
        for extra, name in (([], "fitted.json"), (["--attach"], "fitted_attached.json")):
            out = os.path.join(tmp, name)
            run = subprocess.run([args.cli, "fit", mesh, "--scene", out] + extra, capture_output=True,
                                 text=True, check=False)
            if run.returncode != 0:
                fail(f"supermodal fit --scene {' '.join(extra)}: {run.stdout}{run.stderr}")
                continue
            written.append(out)
        check_file_verdicts(validator, args.probe, written, expect_valid=True)
        count = len(samples) + len(kept) + len(written)
    print(f"{count} scene files checked ({len(samples)} samples, {len(kept)} test scenes, "
          f"{len(written)} written by save_scene and supermodal fit)")


# ---- the schema walk ------------------------------------------------------------------------------------


class Walk:
    """Reads the schema: resolves $ref, finds every object it describes and a valid value for each key."""

    def __init__(self, schema):
        self.schema = schema

    def resolve(self, node):
        """(node, definition name or None) with $ref followed."""
        name = None
        while "$ref" in node:
            ref = node["$ref"]
            assert ref.startswith(DEFS), ref
            name = ref[len(DEFS):]
            node = self.schema["definitions"][name]
        return node, name

    def branches(self, node):
        """The alternatives of a node: its oneOf/anyOf branches, resolved, or the node itself."""
        node, name = self.resolve(node)
        # oneOf/anyOf, or a choice by a key: allOf [{"if": ..., "then": {"$ref": ...}}] (the shapes).
        alternatives = node.get("oneOf") or node.get("anyOf") or \
            [a["then"] for a in node.get("allOf", []) if set(a.get("then", {})) == {"$ref"}]
        if not alternatives:
            return [(node, name)]
        out = []
        for b in alternatives:
            out += self.branches(b)
        return out

    def sites(self):
        """Every object schema with the path to an instance of it: [(label, steps)]. A label is the
        object's definition name, or its path in the schema ("settings/accuracy"). Steps lead from the
        root: (kind, key, schema, label) with kind "prop" (a key of an object; an array's key holds the
        items that follow), "item" (appended to that array) or "entry" (a new entry of a map: materials)."""
        out = []

        def visit(label, node, steps):
            out.append((label, steps))
            for key, prop in node.get("properties", {}).items():
                if key in ANNOTATIONS:
                    continue
                for branch, name in self.branches(prop):
                    child = name or f"{label}/{key}"
                    if branch.get("type") == "object":
                        visit(child, branch, steps + [("prop", key, branch, child)])
                    elif branch.get("type") == "array" and isinstance(branch.get("items"), dict):
                        for item, item_name in self.branches(branch["items"]):
                            if item.get("type") == "object":
                                item_label = item_name or child + "[]"
                                visit(item_label, item, steps + [("prop", key, branch, child),
                                                                 ("item", None, item, item_label)])
            extra = node.get("additionalProperties")
            if isinstance(extra, dict):
                for entry, name in self.branches(extra):
                    entry_label = name or label + "{}"
                    visit(entry_label, entry, steps + [("entry", None, entry, entry_label)])

        visit("root", self.schema, [])
        return out

    def value(self, node, label):
        """A valid value: const, default, first example, or a minimal object."""
        for source in (node, self.resolve(node)[0]):
            if "const" in source:
                return copy.deepcopy(source["const"])
            if "default" in source:
                return copy.deepcopy(source["default"])
            if "examples" in source:
                return copy.deepcopy(source["examples"][0])
        branch, name = self.branches(node)[0]
        if branch.get("type") == "object":
            return self.minimal(branch)
        raise SystemExit(f"schema: {label} has no const, default or examples: give it one")

    def minimal(self, node):
        node, _ = self.resolve(node)
        props = node.get("properties", {})
        return {key: self.value(props[key], key) for key in node.get("required", [])}


def number_schema(node, walk):
    node, _ = walk.resolve(node)
    return node if node.get("type") in ("number", "integer") else None


def bound_cases(node, valid):
    """(value, expected verdict) at and past the bounds of a number schema, and for an integer a fraction
    (refused) and an integral float (accepted)."""
    cases = []
    if "minimum" in node:
        cases += [(node["minimum"], True), (math.nextafter(node["minimum"], -math.inf), False)]
    if "exclusiveMinimum" in node:
        cases += [(node["exclusiveMinimum"], False)]
    if "maximum" in node:
        cases += [(node["maximum"], True), (math.nextafter(node["maximum"], math.inf), False)]
    if "exclusiveMaximum" in node:
        cases += [(node["exclusiveMaximum"], False)]
    if node.get("type") == "integer":
        cases += [(valid + 0.5, False), (float(valid), True)]
        # Integers become doubles in the loader: past an int's range is refused.
        if "maximum" not in node:
            cases += [(2147483648, False)]
    return cases


def mutations(walk, node, start, label):
    """(description, object, expected verdict) for one object schema, starting from a valid instance."""
    props = node.get("properties", {})
    cases = [("as is", start, True)]

    def with_key(key, value):
        obj = copy.deepcopy(start)
        obj[key] = value
        return obj

    for key in ANNOTATIONS:
        cases.append((f"{key} as a number", with_key(key, 5), True))
        cases.append((f"{key} as a string", with_key(key, "note"), True))
    # The loader refuses unknown keys everywhere but in the materials map (its keys are names), so a
    # schema object that lets them through (additionalProperties not false) fails here.
    if not isinstance(node.get("additionalProperties"), dict):
        cases.append(("a made-up key", with_key("no_such_key", 1), False))
    for key in start:
        obj = copy.deepcopy(start)
        obj.pop(key)
        required = key in node.get("required", [])
        cases.append((f"without {'required' if required else 'optional'} {key}", obj, not required))
    for key, prop in props.items():
        if key in ANNOTATIONS:
            continue
        valid = VALUE_OVERRIDES.get((label, key), None)
        if valid is None:
            valid = walk.value(prop, f"{label}.{key}")
        cases.append((f"{key} = {json.dumps(valid)}", with_key(key, valid), True))
        resolved, _ = walk.resolve(prop)
        types = {b.get("type") for b, _ in walk.branches(prop)}
        if "string" not in types:
            cases.append((f"{key} as a string", with_key(key, "text"), False))
        if types == {"string"} or types == {None} and "const" in resolved:
            cases.append((f"{key} as a number", with_key(key, 7), False))
        if "enum" in resolved:
            cases += [(f"{key} = {v!r}", with_key(key, v), True) for v in resolved["enum"]]
            cases.append((f"{key} = a made-up choice", with_key(key, "no_such_choice"), False))
        if resolved.get("minLength") == 1:
            cases.append((f"{key} empty", with_key(key, ""), False))
        if resolved.get("type") == "boolean":
            cases += [(f"{key} = {v}", with_key(key, v), True) for v in (True, False)]
            cases.append((f"{key} = 1", with_key(key, 1), False))
        number = number_schema(prop, walk)
        if number is not None:
            cases += [(f"{key} = {v!r}", with_key(key, v), ok) for v, ok in bound_cases(number, valid)]
        if resolved.get("type") == "array" and isinstance(valid, list) and "minItems" in resolved:
            if len(valid) == resolved["minItems"]:
                cases.append((f"{key} one item short", with_key(key, valid[:-1]), False))
            if len(valid) == resolved.get("maxItems"):
                cases.append((f"{key} one item long", with_key(key, valid + valid[:1]), False))
            if "not" in resolved:
                cases.append((f"{key} all zero", with_key(key, [0] * len(valid)), False))
            items = resolved.get("items")
            item_nodes = items if isinstance(items, list) else [items] * len(valid)
            for i, item in enumerate(item_nodes):
                number = number_schema(item, walk)
                if number is None:
                    continue
                for v, ok in bound_cases(number, valid[i]):
                    bad = copy.deepcopy(valid)
                    bad[i] = v
                    cases.append((f"{key}[{i}] = {v!r}", with_key(key, bad), ok))
    return cases


# Scenes are checked inside this one: bodies "ball" and "box" (for constraints and parents) and a
# material "wood" (a body's material).
SPHERE = {"type": "superquadric", "radii": [0.1, 0.1, 0.1]}
BASE = {
    "materials": {"wood": {}},
    "bodies": [{"name": "ball", "shape": SPHERE}, {"name": "box", "shape": SPHERE}],
}
# Starting objects where the schema's minimal one needs the scene around it: a new body needs a name of
# its own, a constraint a second body (so that anchor_b may be a direction or a surface point), an
# include a file that exists (set with the temporary folder).
START_OVERRIDES = {
    "body": {"name": "crate", "shape": SPHERE},
    "constraint": {"type": "point", "a": "box", "b": "ball"},
}
# Valid values that depend on files or other bodies (filled in with the temporary folder's paths).
VALUE_OVERRIDES = {}


def command_agree(args):
    schema = load_schema(args.source)
    validator = make_validator(schema)
    walk = Walk(schema)
    sites = walk.sites()
    labels = [label for label, _ in sites]
    for needed in ("root", "settings", "contact", "soft_contact", "sleep", "settings/accuracy", "material",
                   "include", "body", "superquadric", "superquadric/bend", "plane", "hyperquadric",
                   "hyperquadric_term", "dynamics", "camera", "constraint", "point_anchor",
                   "direction_anchor", "surface_anchor"):
        if needed not in labels:
            fail(f"the schema walk did not reach {needed}")

    with tempfile.TemporaryDirectory(prefix="supermodal_schema_") as tmp:
        part = os.path.join(tmp, "part.json")
        with open(part, "w", encoding="utf-8") as f:
            json.dump({"bodies": [{"name": "part", "shape": dict(SPHERE, radii=[0.1, 0.2, 0.3])}]}, f)
        mesh = os.path.join(tmp, "mesh.obj")
        write_test_mesh(mesh)
        START_OVERRIDES["include"] = {"file": part}
        VALUE_OVERRIDES.update({("include", "file"): part, ("body", "mesh"): mesh,
                                ("body", "name"): "crate", ("body", "parent"): "ball",
                                ("body", "material"): "wood", ("constraint", "a"): "box"})

        cases = []
        for label, steps in sites:
            node = steps[-1][2] if steps else schema
            start = copy.deepcopy(START_OVERRIDES[label]) if label in START_OVERRIDES else walk.minimal(node)
            for what, obj, expected in mutations(walk, node, start, label):
                cases.append((f"{label}: {what}", place(steps, obj, walk), expected))
        cases += cross_key_cases(part, mesh)

        verdicts = loader_verdicts(args.probe, [doc for _, doc, _ in cases], tmp)
        for (what, doc, expected), (loaded, message) in zip(cases, verdicts):
            ok, why = schema_verdict(validator, doc)
            if ok != loaded:
                fail(f"{what}: the schema {'accepts' if ok else 'refuses (' + why + ')'} but the loader "
                     f"{'accepts' if loaded else 'refuses (' + message + ')'}\n    {json.dumps(doc)}")
            elif ok != expected:
                fail(f"{what}: expected {'valid' if expected else 'invalid'}, both say otherwise "
                     f"(schema: {why or 'ok'}; loader: {message or 'ok'})\n    {json.dumps(doc)}")
    print(f"{len(cases)} scenes over {len(sites)} objects of the schema: the loader and the schema agree"
          if not failures else f"{len(failures)} of {len(cases)} scenes disagree or are unexpected")


def place(steps, leaf, walk):
    """BASE with `leaf` where `steps` lead. The objects on the way start from their minimal value (or
    START_OVERRIDES); array items are appended, so BASE's ball stays first; a map entry gets a new name."""
    if not steps:
        doc = copy.deepcopy(BASE)
        doc.update(leaf)
        return doc
    doc = copy.deepcopy(BASE)
    holder = doc
    for i, (kind, key, node, label) in enumerate(steps):
        if kind == "prop" and node.get("type") == "array":
            items = holder.get(key) if isinstance(holder.get(key), list) else []
            holder[key] = items
            holder = items
            continue
        if i == len(steps) - 1:
            value = leaf
        elif label in START_OVERRIDES:
            value = copy.deepcopy(START_OVERRIDES[label])
        else:
            value = walk.minimal(node)
        if kind == "prop":
            holder[key] = value
        elif kind == "item":
            holder.append(value)
        else:
            holder["site_entry"] = value
        holder = value
    return doc


def cross_key_cases(part, mesh):
    """The rules between keys that the schema states with if/then and not: each way, in a scene."""
    sphere = SPHERE
    plane = {"type": "plane"}

    def body(**keys):
        b = {"name": "box", "shape": sphere}
        b.update(keys)
        return {"bodies": [{"name": "ball", "shape": sphere}, b]}

    def constraint(**keys):
        doc = body()
        c = {"type": "point", "a": "box"}
        c.update(keys)
        doc["constraints"] = [c]
        return doc

    return [
        ("body: density and mass", body(density=500, mass=2), False),
        ("body: a plane, static", body(shape=plane, motion="static"), True),
        ("body: a plane, dynamic", body(shape=plane, motion="dynamic"), False),
        ("body: a plane, kinematic", body(shape=plane, motion="kinematic"), False),
        ("body: a plane with mass", body(shape=plane, mass=2), False),
        ("body: a plane with density", body(shape=plane, density=2), True),
        ("body: a plane with a mesh", body(shape=plane, mesh=mesh), False),
        ("body: a plane, auto", body(shape=plane, dynamics={"type": "auto"}), True),
        ("body: a plane, modal", body(shape=plane, dynamics={"type": "modal"}), False),
        ("body: a plane, full", body(shape=plane, dynamics={"type": "full"}), False),
        ("body: modal and dynamic", body(motion="dynamic", dynamics={"type": "modal"}), True),
        ("body: modal and kinematic", body(motion="kinematic", dynamics={"type": "modal"}), False),
        ("body: full and static", body(motion="static", dynamics={"type": "full"}), False),
        ("body: auto and static", body(motion="static", dynamics={"type": "auto"}), True),
        ("body: full with modes", body(dynamics={"type": "full", "modes": 4}), False),
        ("body: auto with modes", body(dynamics={"type": "auto", "modes": 4}), True),
        ("body: a superquadric with terms", body(shape=dict(sphere, terms=[])), False),
        ("body: a plane with radii", body(shape=dict(plane, radii=[1, 1, 1])), False),
        ("body: a shape without type", body(shape={"radii": [1, 1, 1]}), False),
        ("constraint: weld with swing_limit", constraint(type="weld", b="ball", swing_limit=0.5), False),
        ("constraint: distance with twist_limit",
         constraint(type="distance", b="ball", twist_limit=0.5), False),
        ("constraint: point with both limits", constraint(b="ball", swing_limit=0.5, twist_limit=0.1), True),
        ("constraint: world anchor_b as a point object", constraint(anchor_b={"point": [0, 1, 0]}), True),
        ("constraint: world anchor_b as a direction", constraint(anchor_b={"direction": [0, 1, 0]}), False),
        ("constraint: \"world\" anchor_b as a surface point",
         constraint(b="world", anchor_b={"surface": [0, 0]}), False),
        ("constraint: body anchor_b as a direction", constraint(b="ball", anchor_b={"direction": [0, 1, 0]}),
         True),
        ("constraint: an anchor with two kinds",
         constraint(anchor_a={"point": [0, 0, 0], "direction": [0, 1, 0]}), False),
        ("constraint: an empty anchor object", constraint(anchor_a={}), False),
        ("include: a scene of its own", {"include": [{"file": part, "prefix": "p_"}]}, True),
        ("root: materials named $schema and comment are skipped",
         {"materials": {"$schema": 1, "comment": [], "wood": {}}}, True),
        ("root: a material with an empty name", {"materials": {"": {}}}, False),
        ("root: a material that is not an object", {"materials": {"wood": 1}}, False),
        ("root: not an object", [], False),
    ]


# ---- keys against the loader's source ------------------------------------------------------------------

# Which schema object each key list of the loader describes (lists in engine/src/scene/*.cpp).
KEY_LISTS = {
    "k_top_keys": ["root"],
    "k_include_keys": ["include"],
    "k_settings_keys": ["settings"],
    "k_sleep_keys": ["sleep"],
    "k_accuracy_keys": ["settings/accuracy"],
    "k_contact_keys": ["contact"],
    "k_soft_keys": ["soft_contact"],
    "k_material_keys": ["material"],
    "k_camera_keys": ["camera"],
    "k_body_keys": ["body"],
    "k_term_keys": ["hyperquadric_term"],
    "k_bend_keys": ["superquadric/bend"],
    "k_dynamics_keys": ["dynamics"],
    "k_constraint_keys": ["constraint"],
    "k_anchor_keys": ["point_anchor", "direction_anchor", "surface_anchor"],  # exactly one of them
}
# Which schema enum each choice list is: (object, key).
CHOICE_LISTS = {
    "k_contact_solvers": ("contact", "solver"),
    "k_contact_paths": ("contact", "path"),
    "k_contact_stiffness": ("contact", "stiffness"),
    "k_integrator_names": ("dynamics", "integrator"),
    "k_motion_names": ("body", "motion"),
    "k_dynamics_types": ("dynamics", "type"),
    "k_constraint_types": ("constraint", "type"),
}


def loader_lists(source):
    """name -> list of strings, from `const std::vector<std::string_view> k_... = {...};` (and the nested
    k_shape_keys)."""
    lists = {}
    folder = os.path.join(source, "engine", "src", "scene")
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".cpp"):
            continue
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            text = f.read()
        pattern = r"const std::vector<(?:std::vector<)?std::string_view>>? (k_\w+) = \{(.*?)\};"
        for m in re.finditer(pattern, text, re.S):
            if m.group(1) == "k_shape_keys":
                groups = re.findall(r"\{([^{}]*)\}", m.group(2))
                lists[m.group(1)] = [re.findall(r'"([^"]*)"', g) for g in groups]
            else:
                lists[m.group(1)] = re.findall(r'"([^"]*)"', m.group(2))
    return lists


def command_keys(args):
    schema = load_schema(args.source)
    walk = Walk(schema)
    objects = {label: (steps[-1][2] if steps else schema) for label, steps in walk.sites()}

    def keys_of(label):
        return set(objects[label].get("properties", {})) - set(ANNOTATIONS)

    lists = loader_lists(args.source)
    if len(lists) < 20:
        fail(f"found only {len(lists)} key lists in engine/src/scene: has their form changed?")
    known = set(KEY_LISTS) | set(CHOICE_LISTS) | {"k_shape_keys", "k_shape_types"}
    for name in sorted(set(lists) - known):
        fail(f"engine/src/scene has a list {name} this test does not map to the schema: add it to "
             "KEY_LISTS or CHOICE_LISTS in tests/schema/scene_schema_test.py (and its keys to the schema)")
    covered = set()
    for name, labels in KEY_LISTS.items():
        if name not in lists:
            fail(f"the loader no longer has {name}")
            continue
        schema_keys = set().union(*(keys_of(label) for label in labels))
        covered |= set(labels)
        if set(lists[name]) != schema_keys:
            fail(f"{name} {sorted(lists[name])} != schema {'+'.join(labels)} {sorted(schema_keys)}")
    shape_types = lists.get("k_shape_types", [])
    for shape_type, keys in zip(shape_types, lists.get("k_shape_keys", [])):
        covered.add(shape_type)
        if shape_type not in objects:
            fail(f"the schema has no object for shape type {shape_type}")
        elif set(keys) != keys_of(shape_type):
            fail(f"k_shape_keys[{shape_type}] {sorted(keys)} != schema {sorted(keys_of(shape_type))}")
    shape = schema["definitions"]["shape"]
    shape_consts = {b["properties"]["type"]["const"] for b, _ in walk.branches(shape)}
    if not set(shape_types) == shape_consts == set(shape["properties"]["type"]["enum"]):
        fail(f"k_shape_types {shape_types} != schema shape types {sorted(shape_consts)} and "
             f"{shape['properties']['type']['enum']}")
    for name, (label, key) in CHOICE_LISTS.items():
        enum = objects[label]["properties"][key].get("enum")
        if name not in lists or set(lists[name]) != set(enum or []):
            fail(f"{name} {lists.get(name)} != schema {label}.{key} enum {enum}")
    # Every object of the schema corresponds to a list of the loader (else it would describe keys the
    # loader never reads), except the materials map, whose keys are names.
    for label in objects:
        if label not in covered and label != "root/materials":
            fail(f"schema object {label} has no key list of the loader mapped to it")

    # The reference document mentions every key.
    with open(os.path.join(args.source, "docs", "scene_format.md"), encoding="utf-8") as f:
        doc = f.read()
    for label in objects:
        for key in keys_of(label):
            if not re.search(r"(?<![A-Za-z_])" + re.escape(key) + r"(?![A-Za-z_])", doc):
                fail(f"docs/scene_format.md does not mention {label}.{key}")
        # Every number says its unit in brackets, [-] for a pure number.
        for key, prop in objects[label].get("properties", {}).items():
            node = prop if "type" in prop else walk.resolve(prop)[0]
            if node.get("type") in ("number", "integer") or key in ("gravity", "position", "velocity",
                                                                     "angular_velocity", "radii"):
                if not re.search(r"\[[^\]]+\]", prop.get("description", "")):
                    fail(f"schema {label}.{key}: the description names no unit in brackets")
    if not failures:
        print(f"{len(KEY_LISTS) + len(CHOICE_LISTS) + len(shape_types)} key and choice lists of the loader "
              f"match the schema's {len(objects)} objects")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=["files", "agree", "keys"])
    parser.add_argument("--source", required=True, help="the repository root")
    parser.add_argument("--probe", help="tests/schema's scene_probe program")
    parser.add_argument("--cli", help="the supermodal program")
    args = parser.parse_args()
    # The probe runs in other folders (where a scene's includes and meshes are).
    args.probe = args.probe and os.path.abspath(args.probe)
    args.cli = args.cli and os.path.abspath(args.cli)
    {"files": command_files, "agree": command_agree, "keys": command_keys}[args.command](args)
    if failures:
        print(f"{len(failures)} failure(s)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
