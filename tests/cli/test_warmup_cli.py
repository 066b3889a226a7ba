import json

from voxfab.cli import main


def test_the_command_prints_the_seconds_per_group(capsys):
    assert main(["warmup", "--group", "print", "--processes", "1"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert list(out["groups"]) == ["print"] and out["seconds"] >= out["groups"]["print"] >= 0
