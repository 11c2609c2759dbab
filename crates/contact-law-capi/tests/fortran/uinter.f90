! A UINTER-like FE client of the C ABI through bind(C): compiled with gfortran and run by
! tests/c_abi.rs against the static library. The routine `uinter_like` is what an FE user
! subroutine does: gap in, pressure and tangent out, the history carried by the caller in
! five real state variables (d_min, last_d, d_turn, path, flags; all zero = virgin).
!
! argv(1): a law.json. Commands on standard input, one per line:
!   g GAP   one increment at the gap GAP (m), committed -> "g status p t s1 s2 s3 s4 s5"
!   i GAP   one Newton iteration at GAP, not committed  -> "i status p t s1 s2 s3 s4 s5"
!   r       reset the state variables to zero (virgin)  -> "r"
! The tests map d = D0 + gap with D0 = 0 (the FE surfaces are the law's mean planes).
! Numbers are printed with 17 digits after the point, which read back to the same double.
module scl
  use iso_c_binding
  implicit none
  integer(c_int), parameter :: SCL_OK = 0, SCL_BEYOND_REACH = 7, SCL_ABOVE_TABLE = 8
  type, bind(C) :: scl_state
     real(c_double)     :: d_min, last_d, d_turn
     integer(c_int32_t) :: path, flags
  end type
  interface
     integer(c_int) function scl_law_load(path, law) bind(C, name="scl_law_load")
       import :: c_int, c_char, c_ptr
       character(kind=c_char), dimension(*), intent(in) :: path
       type(c_ptr), intent(out) :: law
     end function
     integer(c_int) function scl_law_eval(law, d, state, p, t) bind(C, name="scl_law_eval")
       import :: c_int, c_ptr, c_double, scl_state
       type(c_ptr), value :: law
       real(c_double), value :: d
       type(scl_state), intent(inout) :: state
       real(c_double), intent(out) :: p, t
     end function
     integer(c_size_t) function scl_last_error_copy(buf, n) bind(C, name="scl_last_error_copy")
       import :: c_size_t, c_char
       character(kind=c_char), dimension(*) :: buf
       integer(c_size_t), value :: n
     end function
     integer(c_int) function scl_abi_version() bind(C, name="scl_abi_version")
       import :: c_int
     end function
     subroutine scl_law_free(law) bind(C, name="scl_law_free")
       import :: c_ptr
       type(c_ptr), value :: law
     end subroutine
  end interface
  type(c_ptr), save :: the_law = c_null_ptr
contains
  ! What an Abaqus UINTER does with the law: STATEV in (the last converged increment's),
  ! STATEV out (kept by the caller only when the increment converges), STRESS = p,
  ! DDSDDR = dp/dd. The status is returned for the caller to act on (SCL_OK, or the
  ! regions outside the measured one with a value, or an error).
  subroutine uinter_like(gap, d0, statev, stress, ddsddr, status)
    real(c_double), intent(in) :: gap, d0
    real(c_double), intent(inout) :: statev(5)
    real(c_double), intent(out) :: stress, ddsddr
    integer(c_int), intent(out) :: status
    type(scl_state) :: st
    real(c_double) :: p, t
    st%d_min = statev(1)
    st%last_d = statev(2)
    st%d_turn = statev(3)
    st%path = int(statev(4), c_int32_t)
    st%flags = int(statev(5), c_int32_t)
    p = 0
    t = 0
    status = scl_law_eval(the_law, d0 + gap, st, p, t)
    stress = 0
    ddsddr = 0
    if (status == SCL_OK .or. status == SCL_BEYOND_REACH .or. status == SCL_ABOVE_TABLE) then
       stress = p
       ddsddr = t
       statev(1) = st%d_min
       statev(2) = st%last_d
       statev(3) = st%d_turn
       statev(4) = real(st%path, c_double)
       statev(5) = real(st%flags, c_double)
    end if
  end subroutine
end module scl

program fe_client
  use scl
  implicit none
  character(len=4096) :: path
  character(len=256) :: line
  character(kind=c_char, len=512) :: msg
  character :: op
  real(c_double) :: statev(5), trial(5), gap, p, t
  integer(c_int) :: rc
  integer(c_size_t) :: n
  integer :: ios, k
  if (command_argument_count() /= 1) then
     write (0, '(a)') 'usage: uinter law.json < commands'
     stop 2
  end if
  call get_command_argument(1, path)
  write (*, '(a,i0)') 'abi ', scl_abi_version()
  rc = scl_law_load(trim(path)//c_null_char, the_law)
  if (rc /= SCL_OK) then
     n = scl_last_error_copy(msg, int(len(msg), c_size_t))
     k = index(msg, c_null_char)
     write (0, '(a,i0,2a)') 'load failed: ', rc, ' ', msg(1:max(k - 1, 0))
     stop 1
  end if
  statev = 0
  do
     read (*, '(a)', iostat=ios) line
     if (ios /= 0) exit
     op = line(1:1)
     if (op == 'r') then
        statev = 0
        write (*, '(a)') 'r'
     else if (op == 'g' .or. op == 'i') then
        read (line(2:), *) gap
        trial = statev
        call uinter_like(gap, 0.0_c_double, trial, p, t, rc)
        if (op == 'g') statev = trial
        write (*, '(a,1x,i0,7(1x,es25.17e3))') op, rc, p, t, trial
     else if (len_trim(line) > 0) then
        write (0, '(2a)') 'unknown command: ', trim(line)
        stop 3
     end if
  end do
  call scl_law_free(the_law)
end program fe_client
