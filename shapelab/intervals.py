r"""Confidence intervals for a proportion :math:`k/n` (lesson 20's recall figures).

A recall "found the site in :math:`k` of :math:`n` structures" estimates a success
probability :math:`p`.  A 95 % confidence interval is a rule that, applied to
:math:`k \sim \operatorname{Binomial}(n, p)`, covers the true :math:`p` in (about) 95 %
of repetitions, whatever :math:`p` is.  Two standard rules:

* **Wilson's score interval** (Wilson 1927): the :math:`p` for which the score test
  :math:`|\hat p - p| \le z \sqrt{p(1-p)/n}` accepts, i.e. the roots of a quadratic,

  .. math:: \frac{\hat p + \frac{z^2}{2n} \pm z\sqrt{\frac{\hat p (1 - \hat p)}{n} + \frac{z^2}{4n^2}}}
                 {1 + \frac{z^2}{n}};

* the **Clopper–Pearson** "exact" interval (Clopper and Pearson 1934): the :math:`p`
  for which neither one-sided binomial test rejects at level :math:`\alpha/2`, from the
  quantiles of the beta distribution; its coverage is at least the nominal level.

The Wald interval :math:`\hat p \pm z\sqrt{\hat p(1-\hat p)/n}` is not offered: at
:math:`k = n` it is the single point 1, and its coverage is poor for small :math:`n`
(Brown, Cai and DasGupta 2001).
"""

from __future__ import annotations

import math

from scipy.special import ndtri
from scipy.stats import beta

__all__ = ["wilson_interval", "clopper_pearson_interval"]


def _check(k, n, confidence):
    for name, v in (("k", k), ("n", n)):
        if isinstance(v, bool) or not float(v).is_integer():
            raise TypeError(f"{name} must be an integer, got {v!r}")
    k, n = int(k), int(n)
    if n < 1 or not 0 <= k <= n:
        raise ValueError(f"need 0 <= k <= n and n >= 1, got k={k}, n={n}")
    if not 0 < confidence < 1:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence}")
    return k, n, float(confidence)


def wilson_interval(k: int, n: int, confidence: float = 0.95) -> tuple:
    """Wilson's score interval for a binomial proportion.

    Parameters
    ----------
    k, n : int
        Successes and trials, ``0 <= k <= n``, ``n >= 1``.
    confidence : float
        The confidence level, default 0.95.

    Returns
    -------
    (float, float)
        The lower and upper ends, within :math:`[0, 1]`.

    See Also
    --------
    clopper_pearson_interval : the exact (conservative) interval.

    References
    ----------
    .. [1] E. B. Wilson, "Probable inference, the law of succession, and statistical
       inference", J. Amer. Statist. Assoc. 22 (1927) 209–212, doi:10.1080/01621459.1927.10502953.
    .. [2] L. D. Brown, T. T. Cai and A. DasGupta, "Interval estimation for a binomial
       proportion", Statist. Sci. 16 (2001) 101–133, doi:10.1214/ss/1009213286.

    Examples
    --------
    >>> lo, hi = wilson_interval(8, 10)
    >>> round(lo, 4), round(hi, 4)
    (0.4902, 0.9433)
    """
    k, n, confidence = _check(k, n, confidence)
    z = float(ndtri(0.5 + confidence / 2))
    ph = k / n
    centre = ph + z * z / (2 * n)
    half = z * math.sqrt(ph * (1 - ph) / n + z * z / (4 * n * n))
    den = 1 + z * z / n
    lo = 0.0 if k == 0 else (centre - half) / den
    hi = 1.0 if k == n else (centre + half) / den
    return (max(0.0, lo), min(1.0, hi))


def clopper_pearson_interval(k: int, n: int, confidence: float = 0.95) -> tuple:
    """The Clopper–Pearson ("exact") interval for a binomial proportion.

    Parameters
    ----------
    k, n : int
        Successes and trials, ``0 <= k <= n``, ``n >= 1``.
    confidence : float
        The confidence level, default 0.95.

    Returns
    -------
    (float, float)
        :math:`(B_{\\alpha/2}(k, n - k + 1),\\ B_{1-\\alpha/2}(k + 1, n - k))`, the
        beta quantiles, with 0 at :math:`k = 0` and 1 at :math:`k = n`.

    See Also
    --------
    wilson_interval

    References
    ----------
    .. [1] C. J. Clopper and E. S. Pearson, "The use of confidence or fiducial limits
       illustrated in the case of the binomial", Biometrika 26 (1934) 404–413,
       doi:10.1093/biomet/26.4.404.

    Examples
    --------
    >>> lo, hi = clopper_pearson_interval(8, 10)
    >>> round(lo, 4), round(hi, 4)
    (0.4439, 0.9748)
    """
    k, n, confidence = _check(k, n, confidence)
    a = 1 - confidence
    lo = 0.0 if k == 0 else float(beta.ppf(a / 2, k, n - k + 1))
    hi = 1.0 if k == n else float(beta.ppf(1 - a / 2, k + 1, n - k))
    return (lo, hi)
