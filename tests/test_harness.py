"""The test harness itself (conftest.py): nbval's kernel start is retried once when the kernel dies starting."""

import pytest

import conftest


def test_a_kernel_that_dies_starting_is_started_once_more():
    calls = []

    def start(**kwargs):
        calls.append(kwargs)
        if len(calls) == 1:
            raise RuntimeError("Kernel died before replying to kernel_info")
        return "km", "kc"

    with pytest.warns(UserWarning, match="died while starting"):
        assert conftest._start_kernel_twice(start)(kernel_name="k") == ("km", "kc")
    assert calls == [{"kernel_name": "k"}, {"kernel_name": "k"}]


def test_other_failures_and_a_second_death_are_not_hidden():
    def other(**kwargs):
        raise RuntimeError("Kernel didn't respond in 60 seconds")

    with pytest.raises(RuntimeError, match="didn't respond"):
        conftest._start_kernel_twice(other)()

    def always(**kwargs):
        raise RuntimeError("Kernel died before replying to kernel_info")

    with pytest.warns(UserWarning), pytest.raises(RuntimeError, match="died"):
        conftest._start_kernel_twice(always)()


def test_nbval_starts_kernels_through_the_retry():
    from nbval import kernel

    assert kernel.start_new_kernel.__wrapped__ is not None
