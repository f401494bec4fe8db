"""Run the ``asperity`` command in-process through its real parser (shared by the CLI tests)."""
import json

from asperity.cli.main import main


def run(capsys, *argv):
    """(exit code, stdout, stderr) of ``asperity ARGV...``."""
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, command, *argv):
    """The JSON object ``asperity COMMAND ARGV... --json`` prints; it must exit with 0."""
    code, out, err = run(capsys, command, *argv, "--json")
    assert code == 0, err
    return json.loads(out)
