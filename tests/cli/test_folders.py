"""The output folder of a command: created for the writing (refused with exit 2 where it cannot
be), and removed again, with what was written, when the writing fails; a folder that was there
before stays."""

import pytest
import typer

from impact.cli.folders import make_folder, removed_on_failure


def test_a_failed_writing_removes_the_folder_it_created(tmp_path):
    folder = tmp_path / "new" / "out"
    with pytest.raises(KeyboardInterrupt), removed_on_failure(folder):
        make_folder(folder, exist_ok=False)
        (folder / "half.h5").write_text("half")
        raise KeyboardInterrupt
    assert not folder.exists()


def test_a_failed_writing_keeps_a_folder_that_was_there(tmp_path):
    (tmp_path / "kept.txt").write_text("kept")
    with pytest.raises(OSError), removed_on_failure(tmp_path):
        make_folder(tmp_path, exist_ok=True)
        raise OSError("disk full")
    assert (tmp_path / "kept.txt").read_text() == "kept"


def test_a_file_in_the_folders_place_is_refused(tmp_path, capsys):
    blocker = tmp_path / "out"
    blocker.write_text("a file")
    with pytest.raises(typer.Exit) as refused:
        make_folder(blocker, exist_ok=True, holds="sweep")
    assert refused.value.exit_code == 2
    assert f"--output: {blocker} exists and is not a folder" in " ".join(capsys.readouterr().err.split())
    assert blocker.read_text() == "a file"


def test_an_existing_folder_without_overwrite_is_refused(tmp_path, capsys):
    with pytest.raises(typer.Exit) as refused:
        make_folder(tmp_path, exist_ok=False, holds="comparison")
    assert refused.value.exit_code == 2
    expected = f"--output: folder {tmp_path} exists; pass --overwrite to replace the comparison in it"
    assert expected in " ".join(capsys.readouterr().err.split())
