"""Every output file is written whole or not at all, with ordinary permissions."""

import os
import stat

import pytest

from moorsolve.errors import CaseError
from moorsolve.io.output_files import replacing, write_case_yaml, write_text


def test_a_failed_write_leaves_neither_the_file_nor_a_temporary(tmp_path):
    target = tmp_path / "out.csv"
    with pytest.raises(RuntimeError):
        with replacing(target) as tmp:
            open(tmp, "w").write("half")
            raise RuntimeError("interrupted")
    assert list(tmp_path.iterdir()) == []


def test_a_failed_write_keeps_the_previous_file(tmp_path):
    target = tmp_path / "out.txt"
    write_text(target, "old\n")
    with pytest.raises(RuntimeError):
        with replacing(target):
            raise RuntimeError("interrupted")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.txt"]


def test_written_files_get_the_permissions_of_a_new_file(tmp_path):
    old = os.umask(0o022)
    try:
        write_text(tmp_path / "a.txt", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "a.txt").stat().st_mode) == 0o644


def test_a_missing_folder_names_the_option(tmp_path):
    with pytest.raises(CaseError, match=r"^--output: folder .* does not exist"):
        write_text(tmp_path / "no" / "a.txt", "x", field="--output")


def test_case_yaml_keeps_points_in_flow_style_and_header_as_comments(tmp_path):
    path = tmp_path / "case.yaml"
    write_case_yaml({"legs": [{"name": "L1", "anchor": (-240.0, -120.0)}]}, path,
                    header="optimised by moorsolve\n# already a comment")
    text = path.read_text()
    assert text.startswith("# optimised by moorsolve\n# already a comment\n")
    assert "anchor: [-240.0, -120.0]" in text


# ---- an edited case file keeps the original's comments and layout --------------------------

ORIGINAL = """\
# A small case, laid out by hand.
environment:
  depth: 20.0          # metres
  wind:    {speed: 30.0, toward_deg: 70}
line_types:
  chain: {weight_in_water: "0.13 t/m", ea: 5.6e8}   # Hu & Tang's chain
legs:
  - {name: L1,  anchor: [-165.0000, -129.4230], fairlead: [-105.0, -25.5, 0.0],
     segments: [{type: chain, length: 122.52}]}
  - name: L2
    anchor: [ 35.0, -145.5]        # aligned by hand
    fairlead: [35.0, -25.5, 0.0]
    segments:
      - {type: chain, length: 122.52}
"""


def _edited(tmp_path, change, name="case (edited)"):
    import copy

    import yaml

    from moorsolve.io.output_files import write_edited_case_yaml
    src = tmp_path / "case.yaml"
    src.write_text(ORIGINAL)
    before = yaml.safe_load(ORIGINAL)
    after = copy.deepcopy(before)
    change(after)
    if name is not None:
        after["name"] = name
    out = tmp_path / "out.yaml"
    write_edited_case_yaml(src, before, after, out, header="edited by a test")
    text = out.read_text()
    assert yaml.safe_load(text) == after
    return text


def test_changed_scalars_are_replaced_in_place(tmp_path):
    def change(d):
        d["legs"][0]["segments"][0]["length"] = 121.5
        d["legs"][1]["anchor"][0] = 36.25
        d["environment"]["wind"]["speed"] = 31.0
    text = _edited(tmp_path, change)
    expected = (ORIGINAL.replace("length: 122.52}]}", "length: 121.5}]}")
                .replace("anchor: [ 35.0, -145.5]", "anchor: [ 36.25, -145.5]")
                .replace("{speed: 30.0,", "{speed: 31.0,"))
    lines = text.splitlines()
    assert lines[0] == "# edited by a test"
    # No name in the file: one line added before the first key, after the comments.
    assert lines[2] == 'name: "case (edited)"'
    assert "\n".join(lines[1:2] + lines[3:]) + "\n" == expected


def test_a_structural_change_keeps_the_comments(tmp_path):
    def change(d):
        d["legs"][1]["segments"].append({"type": "chain", "length": 10.0})
    text = _edited(tmp_path, change)
    for comment in ("# A small case, laid out by hand.", "# metres", "# Hu & Tang's chain",
                    "# aligned by hand"):
        assert comment in text
