"""`gblens compare --junit` as CI systems read it: valid against Jenkins xUnit's junit-10.xsd and the
Ant JUnit schema (xmllint, tests/data/junit), a failing quantity a <failure>, a pair that cannot be
read an <error> (errors counted), a warning visible as a suite property and in <system-out>, and
times measured (positive, within the wall time of the command, cases within their suite)."""
import json
import os
import subprocess
import time
import xml.etree.ElementTree as ET

import pytest

from conftest import SOURCE, run

SCHEMAS = [os.path.join(SOURCE, "tests", "data", "junit", f) for f in ("jenkins-junit-10.xsd", "ant-junit.xsd")]


def validate(path):
    for schema in SCHEMAS:
        p = subprocess.run(["xmllint", "--noout", "--schema", schema, str(path)], capture_output=True, text=True)
        assert p.returncode == 0, f"{os.path.basename(schema)}: {p.stderr}"


def timed(*args):
    start = time.monotonic()
    code, out, err = run(*args, check=False)
    return code, time.monotonic() - start


def suites(path):
    root = ET.parse(path).getroot()
    assert root.tag == "testsuites"
    return root.findall("testsuite")


def test_the_schemas_refuse_what_they_should(tmp_path):
    """The validator can fail: the attribute junit-10.xsd rejected before (skipped on <testsuites>)."""
    bad = tmp_path / "bad.xml"
    bad.write_text('<?xml version="1.0"?>\n<testsuites skipped="0"><testsuite name="x" tests="0" failures="0" '
                   'errors="0"/></testsuites>\n')
    for schema in SCHEMAS:
        p = subprocess.run(["xmllint", "--noout", "--schema", schema, str(bad)], capture_output=True, text=True)
        assert p.returncode != 0, schema


def test_a_failing_pair_is_valid_and_fails_its_quantities(captures, tmp_path):
    out = tmp_path / "fail.xml"
    code, wall = timed("compare", captures["a"], captures["b"], "--junit", out, "--json", tmp_path / "r.json", "-q")
    assert code == 2
    validate(out)
    (suite,) = suites(out)
    report = json.load(open(tmp_path / "r.json"))
    failing = {g["key"] for g in report["groups"] if g["result"] == "fail"}
    failing |= {"flip." + f["target"] for f in report["flip"] if f["result"] == "fail"}
    cases = {c.get("name"): c for c in suite.findall("testcase")}
    assert failing and {k for k, c in cases.items() if c.find("failure") is not None} == failing
    assert int(suite.get("failures")) == len(failing) and int(suite.get("errors")) == 0
    # Times: measured, not zero; every case inside its suite, the suite inside the command's wall time.
    suite_time = float(suite.get("time"))
    case_times = [float(c.get("time")) for c in cases.values()]
    assert 0.0 < suite_time <= wall
    assert all(t >= 0.0 for t in case_times) and sum(case_times) <= suite_time + 5e-4 * len(case_times)  # ms rounding


def test_a_warning_is_visible_to_ci(captures, tmp_path):
    """Nothing fails (fail threshold far above any error), everything that differs warns."""
    out = tmp_path / "warn.xml"
    code, _ = timed("compare", captures["a"], captures["b"], "--failpercent", "100", "--warn", "0",
                    "--flip", "off", "--junit", out, "-q")
    assert code == 1
    validate(out)
    (suite,) = suites(out)
    props = {p.get("name"): p.get("value") for p in suite.find("properties")}
    warned = [k[len("warning."):] for k in props if k.startswith("warning.")]
    assert warned and int(props["warnings"]) == len(warned)
    assert suite.find("system-out").text.startswith("WARNING ")
    cases = {c.get("name"): c for c in suite.findall("testcase")}
    for key in warned:
        assert key in cases and len(cases[key]) == 0  # passed as a test, the warning beside it
    assert int(suite.get("failures")) == 0


def test_an_unreadable_pair_is_an_error(captures, tmp_path):
    listing = tmp_path / "pairs.txt"
    listing.write_text(f"{captures['a']} {captures['a']} same\n{captures['a']} {tmp_path / 'missing'} gone\n")
    out = tmp_path / "pairs.xml"
    code, _ = timed("compare", "--pairs", listing, "--flip", "off", "--junit", out, "-q")
    assert code == 4
    validate(out)
    same, gone = suites(out)
    assert (same.get("name"), gone.get("name")) == ("same", "gone")
    assert int(same.get("errors")) == 0 and int(same.get("failures")) == 0
    assert int(gone.get("errors")) == 1 and int(gone.get("failures")) == 0 and int(gone.get("tests")) == 1
    error = gone.find("testcase").find("error")
    assert error is not None and "missing" in error.get("message")
    assert "FILE ERROR" in gone.find("system-out").text
