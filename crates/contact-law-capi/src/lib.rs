//! C ABI of [`contact_law`]: load `law.json` and evaluate the adhesive-contact law from C,
//! C++, Fortran (`bind(C)`) or Python (`ctypes`). The declarations are in
//! `include/stiction_contact_law.h`; a test compiles a C program against that header and
//! this crate's static library and checks its results against the Rust evaluator bit for
//! bit.
//!
//! Every function returns a status code ([`SCL_OK`] or an `SCL_ERR_*` value; the
//! evaluations also [`SCL_BEYOND_REACH`] or [`SCL_ABOVE_TABLE`], with their outputs
//! written, for a point outside the measured region) and never unwinds across the boundary (each body runs under `catch_unwind`); null pointers are
//! reported as [`SCL_ERR_NULL`]. The message of the last failed call on the calling thread
//! is [`scl_last_error`]. A loaded law is immutable: several threads may evaluate it at
//! once, each with its own `scl_state`.
//!
//! ```
//! use contact_law_capi::*;
//! use std::ffi::CString;
//! # let dir = std::env::temp_dir().join(format!("scl-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir).unwrap();
//! # let file = dir.join("law.json");
//! # let toy = contact_law::toy::ToyLaw::default();
//! # let t = contact_law::tabulate::Tabulation::adaptive(1.5e-9, 15e-9);
//! # contact_law::tabulate::tabulate(&toy, &t).unwrap().write_json(&file).unwrap();
//! let path = CString::new(file.to_str().unwrap()).unwrap();
//! let mut law = std::ptr::null_mut();
//! assert_eq!(unsafe { scl_law_load(path.as_ptr(), &mut law) }, SCL_OK);
//! let mut state = SclState::default(); // zeroed: a virgin surface
//! let (mut p, mut t) = (0.0, 0.0);
//! for d in [9e-9, 3e-9, 3.2e-9] {
//!     assert_eq!(unsafe { scl_law_eval(law, d, &mut state, &mut p, &mut t) }, SCL_OK);
//! }
//! assert_eq!((state.d_min, state.path), (3e-9, SCL_PATH_RETRACT));
//! unsafe { scl_law_free(law) };
//! # std::fs::remove_dir_all(&dir).ok();
//! ```

use contact_law::{ContactLaw, LawError, Path, Region, State};
use std::cell::RefCell;
use std::ffi::{c_char, c_int, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Success.
pub const SCL_OK: c_int = 0;
/// A required pointer argument was null.
pub const SCL_ERR_NULL: c_int = 1;
/// The file could not be read (missing, unreadable, too large).
pub const SCL_ERR_IO: c_int = 2;
/// The file is not a valid `law.json` (syntax, format, version, a value).
pub const SCL_ERR_FORMAT: c_int = 3;
/// A separation or history outside the tabulated range.
pub const SCL_ERR_OUT_OF_RANGE: c_int = 4;
/// An invalid argument: a non-finite separation, an unknown path, an inconsistent state.
pub const SCL_ERR_INVALID: c_int = 5;
/// An internal error (a caught panic); please report it.
pub const SCL_ERR_INTERNAL: c_int = 6;
/// Not an error: the outputs are written, but the point lies beyond the reach of its curve
/// (every asperity out of contact): the pressure and the tangent are exactly 0, the model's
/// own value there, not a measured interpolation ([`contact_law::Region::BeyondReach`]).
pub const SCL_BEYOND_REACH: c_int = 7;
/// Not an error: the outputs are written, but the history is shallower than the shallowest
/// tabulated branch: the value is the law's blend towards zero at the virgin reach, not
/// measured against the surface ([`contact_law::Region::AboveTable`]).
pub const SCL_ABOVE_TABLE: c_int = 8;

/// The status of a successful evaluation in `region`: [`SCL_OK`] inside the measured
/// region, [`SCL_BEYOND_REACH`] or [`SCL_ABOVE_TABLE`] outside it (outputs written). A
/// deeper history than the table is an error ([`SCL_ERR_OUT_OF_RANGE`], nothing written),
/// never a value.
pub fn region_status(region: Region) -> c_int {
    match region {
        Region::Measured => SCL_OK,
        Region::BeyondReach => SCL_BEYOND_REACH,
        Region::AboveTable => SCL_ABOVE_TABLE,
        Region::BelowTable => SCL_ERR_OUT_OF_RANGE,
    }
}

/// `scl_state.path`: approach (coming from far or reloading).
pub const SCL_PATH_APPROACH: i32 = 0;
/// `scl_state.path`: retract.
pub const SCL_PATH_RETRACT: i32 = 1;

/// `scl_state.flags` bit: the surface has been loaded (d_min, last_d and path are valid).
/// Without it the state is virgin and the other fields are ignored.
pub const SCL_STATE_TOUCHED: i32 = 1;
/// `scl_state.flags` bit: d_turn is valid (the current path began at a reversal).
pub const SCL_STATE_TURNED: i32 = 2;

/// Version of this ABI (functions, struct layout, codes).
pub const SCL_ABI_VERSION: c_int = 2;

/// The opaque law handle `scl_law`.
pub struct SclLaw(ContactLaw);

/// `scl_state`: the caller-owned history of one point of the surface. All-zero bytes is a
/// virgin surface, so zero-initialised storage (an FE code's state variables) needs no
/// call. Every stored number is finite.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SclState {
    /// Deepest separation reached (m); valid with [`SCL_STATE_TOUCHED`].
    pub d_min: f64,
    /// Separation of the previous call (m); valid with [`SCL_STATE_TOUCHED`].
    pub last_d: f64,
    /// Separation of the last reversal (m); valid with [`SCL_STATE_TURNED`].
    pub d_turn: f64,
    /// [`SCL_PATH_APPROACH`] or [`SCL_PATH_RETRACT`].
    pub path: i32,
    /// Bits [`SCL_STATE_TOUCHED`], [`SCL_STATE_TURNED`].
    pub flags: i32,
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_error(message: &str) {
    let clean: Vec<u8> = message
        .bytes()
        .map(|b| if b == 0 { b'?' } else { b })
        .collect();
    let c = CString::new(clean).unwrap_or_default();
    // a thread being torn down has no slot: the code still tells what happened
    let _ = LAST_ERROR.try_with(|e| *e.borrow_mut() = c);
}

fn fail(code: c_int, message: &str) -> c_int {
    set_error(message);
    code
}

/// The status code of a [`LawError`]: I/O and size to [`SCL_ERR_IO`], JSON and format to
/// [`SCL_ERR_FORMAT`], range to [`SCL_ERR_OUT_OF_RANGE`], the rest to [`SCL_ERR_INVALID`].
pub fn status_code(e: &LawError) -> c_int {
    match e {
        LawError::Io { .. } | LawError::TooLarge { .. } => SCL_ERR_IO,
        LawError::Json(_) | LawError::Format { .. } => SCL_ERR_FORMAT,
        LawError::OutOfRange(_) => SCL_ERR_OUT_OF_RANGE,
        _ => SCL_ERR_INVALID,
    }
}

fn law_error(e: &LawError) -> c_int {
    fail(status_code(e), &e.to_string())
}

/// Runs `f`, turning a panic into [`SCL_ERR_INTERNAL`].
fn guard(f: impl FnOnce() -> c_int) -> c_int {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(code) => code,
        Err(_) => fail(
            SCL_ERR_INTERNAL,
            "internal error (panic) in contact-law-capi",
        ),
    }
}

fn path_from_c(path: i32) -> Option<Path> {
    match path {
        SCL_PATH_APPROACH => Some(Path::Approach),
        SCL_PATH_RETRACT => Some(Path::Retract),
        _ => None,
    }
}

fn path_to_c(path: Path) -> i32 {
    match path {
        Path::Approach => SCL_PATH_APPROACH,
        Path::Retract => SCL_PATH_RETRACT,
    }
}

impl SclState {
    /// The Rust state of this C state; `None` if inconsistent.
    pub fn to_state(&self) -> Option<State> {
        if self.flags & SCL_STATE_TOUCHED == 0 {
            return Some(State::VIRGIN);
        }
        let path = path_from_c(self.path)?;
        let turned = self.flags & SCL_STATE_TURNED != 0;
        if !self.d_min.is_finite()
            || !self.last_d.is_finite()
            || (turned && !self.d_turn.is_finite())
        {
            return None;
        }
        Some(State {
            d_min: self.d_min,
            path,
            last_d: self.last_d,
            d_turn: if turned { self.d_turn } else { f64::INFINITY },
        })
    }

    /// The C state of a Rust state (virgin states become all zero).
    pub fn from_state(s: &State) -> SclState {
        if s.is_virgin() {
            return SclState::default();
        }
        let turned = s.d_turn.is_finite();
        SclState {
            d_min: s.d_min,
            last_d: s.last_d,
            d_turn: if turned { s.d_turn } else { 0.0 },
            path: path_to_c(s.path),
            flags: SCL_STATE_TOUCHED | if turned { SCL_STATE_TURNED } else { 0 },
        }
    }
}

/// Reads and validates `law.json` at `path` (a NUL-terminated file name) and stores a new
/// handle in `*out` (left untouched on error). Free it with [`scl_law_free`].
///
/// # Safety
/// `path` must be null or a NUL-terminated string; `out` null or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn scl_law_load(path: *const c_char, out: *mut *mut SclLaw) -> c_int {
    guard(|| {
        if path.is_null() || out.is_null() {
            return fail(SCL_ERR_NULL, "scl_law_load: null path or out pointer");
        }
        // SAFETY: non-null and NUL-terminated by the contract above
        let bytes = unsafe { CStr::from_ptr(path) }.to_bytes();
        #[cfg(unix)]
        let file = {
            use std::os::unix::ffi::OsStrExt;
            std::path::PathBuf::from(std::ffi::OsStr::from_bytes(bytes))
        };
        #[cfg(not(unix))]
        let file = match std::str::from_utf8(bytes) {
            Ok(s) => std::path::PathBuf::from(s),
            Err(_) => return fail(SCL_ERR_INVALID, "scl_law_load: the path is not UTF-8"),
        };
        match ContactLaw::from_path(&file) {
            Ok(law) => {
                // SAFETY: `out` is non-null and valid for a write by the contract
                unsafe { *out = Box::into_raw(Box::new(SclLaw(law))) };
                SCL_OK
            }
            Err(e) => law_error(&e),
        }
    })
}

/// Frees a handle from [`scl_law_load`]; null is a no-op.
///
/// # Safety
/// `law` must be null or a handle from [`scl_law_load`] not freed before.
#[no_mangle]
pub unsafe extern "C" fn scl_law_free(law: *mut SclLaw) {
    if law.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: a live handle from scl_law_load by the contract
        drop(unsafe { Box::from_raw(law) });
    }));
}

/// Sets `*state` to a virgin surface (all zero). Null is a no-op.
///
/// # Safety
/// `state` must be null or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn scl_state_init(state: *mut SclState) {
    if !state.is_null() {
        // SAFETY: non-null and valid for a write by the contract
        unsafe { state.write(SclState::default()) };
    }
}

/// Pressure `*pressure` (Pa, compressive positive) and tangent `*tangent` = dp/dd (Pa/m)
/// at separation `d` (m), updating the history `*state` as
/// [`contact_law::ContactLaw::pressure`] does. Returns [`SCL_OK`] inside the measured
/// region, [`SCL_BEYOND_REACH`] or [`SCL_ABOVE_TABLE`] outside it (the outputs and the
/// state are written: see [`region_status`]); on error nothing is written.
///
/// # Safety
/// `law` must be null or a live handle; the other pointers null or valid.
#[no_mangle]
pub unsafe extern "C" fn scl_law_eval(
    law: *const SclLaw,
    d: f64,
    state: *mut SclState,
    pressure: *mut f64,
    tangent: *mut f64,
) -> c_int {
    guard(|| {
        if law.is_null() || state.is_null() || pressure.is_null() || tangent.is_null() {
            return fail(
                SCL_ERR_NULL,
                "scl_law_eval: null law, state, pressure or tangent pointer",
            );
        }
        // SAFETY: non-null pointers valid by the contract
        let (law, c_state) = unsafe { (&(*law).0, *state) };
        let Some(mut s) = c_state.to_state() else {
            return fail(
                SCL_ERR_INVALID,
                "scl_law_eval: inconsistent scl_state (unknown path or non-finite field of a touched state)",
            );
        };
        match law.step(d, &mut s) {
            Ok(e) => {
                // SAFETY: as above
                unsafe {
                    *pressure = e.pressure;
                    *tangent = e.tangent;
                    *state = SclState::from_state(&s);
                }
                region_status(e.region)
            }
            Err(e) => law_error(&e),
        }
    })
}

/// Stateless evaluation ([`contact_law::ContactLaw::evaluate`]) at `d` (m) with history
/// `d_min` (m; `INFINITY` for a virgin surface) on `path`. Writes the pressure (Pa), the
/// tangent (Pa/m) and, if `d_min_out` is not null, the history after the call (d when
/// d < d_min). The status says the region as for [`scl_law_eval`]; on error nothing is
/// written.
///
/// # Safety
/// `law` must be null or a live handle; the other pointers null or valid.
#[no_mangle]
pub unsafe extern "C" fn scl_law_eval_stateless(
    law: *const SclLaw,
    d: f64,
    d_min: f64,
    path: i32,
    pressure: *mut f64,
    tangent: *mut f64,
    d_min_out: *mut f64,
) -> c_int {
    guard(|| {
        if law.is_null() || pressure.is_null() || tangent.is_null() {
            return fail(
                SCL_ERR_NULL,
                "scl_law_eval_stateless: null law, pressure or tangent pointer",
            );
        }
        let Some(path) = path_from_c(path) else {
            return fail(
                SCL_ERR_INVALID,
                "scl_law_eval_stateless: path must be 0 (approach) or 1 (retract)",
            );
        };
        // SAFETY: non-null and live by the contract
        let law = unsafe { &(*law).0 };
        match law.evaluate(d, d_min, path) {
            Ok(e) => {
                // SAFETY: non-null pointers valid by the contract
                unsafe {
                    *pressure = e.pressure;
                    *tangent = e.tangent;
                    if !d_min_out.is_null() {
                        *d_min_out = e.d_min;
                    }
                }
                region_status(e.region)
            }
            Err(e) => law_error(&e),
        }
    })
}

/// The tabulated d_min range (m): deeper histories are out of range.
///
/// # Safety
/// `law` must be null or a live handle; the other pointers null or valid.
#[no_mangle]
pub unsafe extern "C" fn scl_law_d_min_range(
    law: *const SclLaw,
    lo: *mut f64,
    hi: *mut f64,
) -> c_int {
    guard(|| {
        if law.is_null() || lo.is_null() || hi.is_null() {
            return fail(SCL_ERR_NULL, "scl_law_d_min_range: null pointer");
        }
        // SAFETY: valid by the contract
        unsafe {
            let (a, b) = (*law).0.d_min_range();
            *lo = a;
            *hi = b;
        }
        SCL_OK
    })
}

/// Writes 1 to `*exact` if the one-number history is exact for `*state`, 0 after a
/// partial reload or a partial retraction (see
/// [`contact_law::ContactLaw::is_history_exact`]). The status tells whether the state's
/// history lies in the measured range of the table
/// ([`contact_law::ContactLaw::history_region`]): [`SCL_OK`] inside it (and for a virgin
/// state), [`SCL_ABOVE_TABLE`] for a history shallower than the table (`*exact` written:
/// the history may be exact, but the law there is not measured), [`SCL_BEYOND_REACH`] for
/// one at or beyond the virgin reach (never in contact: the law is exactly zero),
/// [`SCL_ERR_OUT_OF_RANGE`] for one deeper than the table (nothing written).
///
/// # Safety
/// `law` must be null or a live handle; the other pointers null or valid.
#[no_mangle]
pub unsafe extern "C" fn scl_law_history_exact(
    law: *const SclLaw,
    state: *const SclState,
    exact: *mut c_int,
) -> c_int {
    guard(|| {
        if law.is_null() || state.is_null() || exact.is_null() {
            return fail(SCL_ERR_NULL, "scl_law_history_exact: null pointer");
        }
        // SAFETY: valid by the contract
        let (law, c_state) = unsafe { (&(*law).0, *state) };
        let Some(s) = c_state.to_state() else {
            return fail(
                SCL_ERR_INVALID,
                "scl_law_history_exact: inconsistent scl_state",
            );
        };
        let region = if s.is_virgin() {
            Region::Measured
        } else {
            law.history_region(s.d_min)
        };
        if region == Region::BelowTable {
            return fail(
                SCL_ERR_OUT_OF_RANGE,
                &format!(
                    "scl_law_history_exact: the state's d_min = {:e} m is deeper than the table (region below_table)",
                    s.d_min
                ),
            );
        }
        // SAFETY: valid by the contract
        unsafe { *exact = c_int::from(law.is_history_exact(&s)) };
        region_status(region)
    })
}

/// The message of the last failed call on this thread (empty if none). The pointer stays
/// valid until the next failing call on this thread; copy it to keep it.
#[no_mangle]
pub extern "C" fn scl_last_error() -> *const c_char {
    static EMPTY: &[u8] = b"\0";
    catch_unwind(|| {
        LAST_ERROR
            .try_with(|e| e.borrow().as_ptr())
            .unwrap_or(EMPTY.as_ptr().cast())
    })
    .unwrap_or(EMPTY.as_ptr().cast())
}

/// Copies the last error message into `buf` (at most `len` bytes including the NUL; a
/// longer message is cut) and returns the full message length without the NUL, so that a
/// caller can size its buffer. For languages that handle char pointers poorly (Fortran).
///
/// # Safety
/// `buf` must be null or valid for `len` bytes.
#[no_mangle]
pub unsafe extern "C" fn scl_last_error_copy(buf: *mut c_char, len: usize) -> usize {
    catch_unwind(AssertUnwindSafe(|| {
        LAST_ERROR
            .try_with(|e| {
                let e = e.borrow();
                let bytes = e.as_bytes();
                if !buf.is_null() && len > 0 {
                    let n = bytes.len().min(len - 1);
                    // SAFETY: buf valid for len >= n + 1 bytes by the contract
                    unsafe {
                        std::ptr::copy_nonoverlapping(bytes.as_ptr().cast::<c_char>(), buf, n);
                        *buf.add(n) = 0;
                    }
                }
                bytes.len()
            })
            .unwrap_or(0)
    }))
    .unwrap_or(0)
}

/// [`SCL_ABI_VERSION`]: compare with the header's `SCL_ABI_VERSION` at start-up.
#[no_mangle]
pub extern "C" fn scl_abi_version() -> c_int {
    SCL_ABI_VERSION
}
