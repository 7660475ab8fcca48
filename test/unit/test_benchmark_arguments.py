"""The benchmark's parts refuse a world or a laser profile that does not exist in one usage
line, before any run: a wrong name once gave a traceback (sim, mapping) or a table of failed
runs and status 0 (find, follow, wander). Needs the package on ROS_PACKAGE_PATH (the worlds
are found through rospkg), no master."""
import pytest

from wall_follower.evaluation.benchmarks.cli import main

# Parts are imported by name on demand: all of them, and each refusal, come before any run.
CASES = [
    # The simulator's part imports rosgraph before it reads its arguments.
    pytest.param(['sim', '--world', 'nowhere'], "argument --world: no world ", 'nowhere.world',
                 marks=pytest.mark.ros),
    (['mapping', '--worlds', 'pillars'], 'argument --worlds: no world ', 'pillars_odom.world'),
    (['find', '--worlds', 'nowhere'], 'argument --worlds: no world ', 'nowhere.world'),
    (['find', '--laser-profile', 'sonar'], "no laser profile 'sonar'", ''),
    # The follower's part grades generated worlds through grade, which reads launch files
    # with roslaunch and names with rosgraph.
    pytest.param(['follow', '--worlds', 'room', 'nowhere'], 'argument --worlds: no world ',
                 'nowhere.world', marks=pytest.mark.ros),
    pytest.param(['follow', '--profiles', 'sonar'], "argument --profiles: no laser profile 'sonar'",
                 '', marks=pytest.mark.ros),
    (['wander', '--worlds', '/nowhere/x.world'], 'argument --worlds: no world /nowhere/x.world',
     ''),
    # A margin that leaves no band would find no T* anywhere.
    pytest.param(['follow', '--bound-margin', '0.05'], "argument --bound-margin: '0.05' is not "
                 'a margin from 0 to under 0.05 m', '(half the band)', marks=pytest.mark.ros),
    pytest.param(['follow', '--bound-margin', 'wide'], "argument --bound-margin: 'wide' is not "
                 'a margin', '(half the band)', marks=pytest.mark.ros),
]


@pytest.mark.parametrize('argv, says, names', CASES)
def test_an_unknown_world_or_profile_or_a_bad_margin_is_a_usage_error(capsys, argv, says, names):
    with pytest.raises(SystemExit) as ended:
        main(argv)
    assert ended.value.code == 2
    error = capsys.readouterr().err.splitlines()[-1]
    assert error.startswith('benchmark %s: error: ' % argv[0])
    assert says in error and error.endswith(names)


@pytest.mark.ros
@pytest.mark.parametrize('argv, profiles', [
    (['--generated', '2'], ['stage', 'lds01', 'lds02', 'gazebo', 'course720']),
    (['--generated', '2', '--profiles', 'lds01', 'course720'], ['lds01', 'course720'])])
def test_generated_worlds_are_run_in_the_profiles_asked_for(monkeypatch, tmp_path, argv,
                                                            profiles):
    from wall_follower.evaluation.benchmarks import follow, follow_generated
    ran = []
    monkeypatch.setattr(follow_generated, 'run', lambda count, seed, asked, *rest: ran.append(
        (count, list(asked))))
    follow.main(argv + ['--out', str(tmp_path)])
    assert ran == [(2, profiles)]
