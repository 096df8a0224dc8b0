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
