"""The pytest plugin: the `plc` fixture from a marker, and IEC unit tests
collected as pytest items (run here through pytest's own `pytester`)."""

import textwrap


def test_plc_fixture_from_a_marker(pytester, repo):
    pytester.makepyfile(
        test_chariot=textwrap.dedent(
            f"""
            import datetime
            import pytest

            @pytest.mark.plc({str(repo / "programs" / "chariot.sfc")!r}, cycle_time="100ms")
            def test_leaves_a_and_waits_at_b(plc):
                assert plc.cycle_time == datetime.timedelta(milliseconds=100)
                plc["FcA"] = True
                plc["Dcy"] = True
                plc.scan(2)
                assert plc["KMAV"] and plc.chart_states() == {{"CHARIOT": ["AV"]}}
                plc["FcA"] = False
                plc["FcB"] = True
                plc.until("ATT.X", timeout="1s")
                took = plc.until("AR.X", timeout="11m")
                assert datetime.timedelta(minutes=9, seconds=59) <= took <= datetime.timedelta(minutes=10, seconds=1)

            @pytest.mark.plc({{"p.st": "PROGRAM P VAR_OUTPUT n : INT; END_VAR n := n + 1; END_PROGRAM"}})
            def test_sources_as_a_dict(plc):
                plc.scan(3)
                assert plc["n"] == 3

            @pytest.mark.plc({{"p.st": "PROGRAM P VAR_OUTPUT q : BOOL; END_VAR END_PROGRAM"}})
            def test_until_times_out(plc):
                with pytest.raises(TimeoutError):
                    plc.until("q", timeout="2s")
                assert plc.time == datetime.timedelta(seconds=2)

            def test_without_marker(plc):
                pass
            """
        )
    )
    result = pytester.runpytest("-q")
    result.assert_outcomes(passed=3, errors=1)
    result.stdout.fnmatch_lines(["*the plc fixture needs a marker*"])


def test_marker_paths_are_relative_to_the_test_file(pytester):
    pytester.makefile(".st", counter="PROGRAM C VAR_OUTPUT n : INT; END_VAR n := n + 2; END_PROGRAM")
    pytester.makepyfile(
        test_rel="""
        import pytest

        @pytest.mark.plc("counter.st", cycle_time="T#50ms")
        def test_counts(plc):
            plc.scan(2)
            assert plc["n"] == 4 and plc.time_ns == 100_000_000
        """
    )
    pytester.runpytest("-q").assert_outcomes(passed=1)


def test_the_projects_st_tests_run_as_items(pytester, repo):
    result = pytester.runpytest("-v", str(repo / "tests" / "plc"))
    result.assert_outcomes(passed=10)
    result.stdout.fnmatch_lines(
        [
            "*cmd_monitor_test.st::TEST_CMD_MONITOR_alarm_after_T_CMD_MAX PASSED*",
            "*comparator_test.st::TEST_COMPA_all_256_pairs PASSED*",
        ]
    )


def test_failing_st_tests_report_their_assertions(pytester):
    pytester.makefile(
        ".st",
        ramp_test="""
        (* plcrun: sources = ramp.st *)
        FUNCTION_BLOCK TEST_Ramp_reaches_100
          VAR CONSTANT TEST_CYCLES : INT := 12; END_VAR
          VAR r : Ramp; n : INT; END_VAR
          r(go := TRUE);
          n := n + 1;
          IF n = 12 THEN AssertEquals(INT#100, r.v, 'saturates'); END_IF
        END_FUNCTION_BLOCK
        PROGRAM TEST_Ramp_idle
          VAR r : Ramp; END_VAR
          r(go := FALSE);
          AssertEquals(INT#10, r.v, 'deliberately wrong');
        END_PROGRAM
        PROGRAM TEST_Ramp_divides
          VAR r : Ramp; z : INT; END_VAR
          r(go := TRUE);
          z := r.v / z;
        END_PROGRAM
        """,
    )
    pytester.makefile(
        ".st",
        ramp="""
        FUNCTION_BLOCK Ramp VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT v : INT; END_VAR
          IF go AND v < 100 THEN v := v + 10; END_IF
        END_FUNCTION_BLOCK
        """,
    )
    result = pytester.runpytest("-v")
    result.assert_outcomes(passed=1, failed=2)
    result.stdout.fnmatch_lines(
        [
            "*TEST_Ramp_idle failed after 1 cycles:*",
            "*ramp_test.st:12:*deliberately wrong: expected 10, got 0 (cycle 0)*",
            "*TEST_Ramp_divides errored*",
            "*R001*division by zero*",
        ]
    )


def test_st_files_that_do_not_compile_are_collection_errors(pytester):
    pytester.makefile(".st", broken_test="PROGRAM TEST_broken x := 1; END_PROGRAM")
    result = pytester.runpytest()
    result.assert_outcomes(errors=1)
    result.stdout.fnmatch_lines(["*could not compile broken_test.st*", "*E201*"])


def test_ini_patterns_and_sources(pytester):
    pytester.makeini(
        """
        [pytest]
        plcrun_test_files = *_spec.st
        plcrun_sources = lib/add.st
        """
    )
    lib = pytester.mkdir("lib")
    (lib / "add.st").write_text("FUNCTION Add2 : INT VAR_INPUT a : INT; END_VAR Add2 := a + 2; END_FUNCTION\n")
    pytester.makefile(".st", add_spec="PROGRAM TEST_add AssertEquals(INT#5, Add2(3), 'sum'); END_PROGRAM")
    pytester.makefile(".st", add_test="PROGRAM TEST_not_collected AssertTrue(FALSE, 'no'); END_PROGRAM")
    pytester.runpytest().assert_outcomes(passed=1)
