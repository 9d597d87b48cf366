!> Small string utilities shared by the input reader, validation and the summary: case,
!> blanks, quoting, Fortran names, and plain forms of numbers for messages.
module strings_m
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    use, intrinsic :: iso_c_binding, only: c_char, c_null_char
    use kinds_m, only: dp
    use reals_m, only: is_zero
    implicit none
    private
    public :: lower, keyword, squeeze, excerpt, quoted, doubled_quotes
    public :: identifier_at, is_name_char
    public :: int_str, format_real, short_real, from_c_chars

contains

    !> x in a plain form for messages: 15 significant digits, trailing zeros
    !> dropped, fixed notation for 1e-4 <= |x| < 1e6, else 1.2298e-17; NaN, Inf, -Inf.
    pure function format_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        character(len=:), allocatable :: digits, sign
        integer :: e, expo, ios

        if (ieee_is_nan(x)) then
            s = 'NaN'
            return
        else if (.not. ieee_is_finite(x)) then
            s = merge('-Inf', ' Inf', x < 0.0_dp)
            s = trim(adjustl(s))
            return
        else if (.not. abs(x) > 0.0_dp) then
            s = '0'
            return
        end if
        write (buf, '(es23.14e3)', iostat=ios) x
        buf = adjustl(buf)
        e = index(buf, 'E')
        read (buf(e + 1:), *, iostat=ios) expo
        sign = ''
        if (buf(1:1) == '-') then
            sign = '-'
            buf = buf(2:)
            e = e - 1
        end if
        digits = buf(1:1) // buf(3:e - 1)
        digits = digits(:max(1, verify(digits, '0', back=.true.)))
        if (expo >= 0 .and. expo < 6) then
            if (len(digits) <= expo + 1) then
                s = digits // repeat('0', expo + 1 - len(digits))
            else
                s = digits(:expo + 1) // '.' // digits(expo + 2:)
            end if
        else if (expo < 0 .and. expo >= -4) then
            s = '0.' // repeat('0', -expo - 1) // digits
        else
            s = digits(1:1)
            if (len(digits) > 1) s = s // '.' // digits(2:)
            write (buf, '(i0)', iostat=ios) expo
            s = s // 'e' // trim(buf)
        end if
        s = sign // s
    end function format_real

    !> x with 4 significant digits and no padding: 0.1973, 12.5, 3, 1.234E-05.
    pure function short_real(x) result(text)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        integer :: decimals

        if (abs(x) >= 1.0e-3_dp .and. abs(x) < 1.0e6_dp) then
            decimals = max(0, 3 - floor(log10(abs(x))))
            write (buffer, '(f0.' // int_str(decimals) // ')') x
            text = trim(adjustl(buffer))
            if (decimals > 0) then   ! no trailing zeros, no bare point
                text = text(:verify(text, '0', back=.true.))
                text = text(:verify(text, '.', back=.true.))
            end if
            if (text(1:1) == '.') text = '0'//text
        else if (is_zero(x)) then
            text = '0'
        else
            write (buffer, '(es10.3)') x
            text = trim(adjustl(buffer))
        end if
    end function short_real
    !> The Fortran name (letters, digits, '_') starting at text(start:); '' if none.
    pure function identifier_at(text, start) result(name)
        character(len=*), intent(in) :: text
        integer, intent(in) :: start
        character(len=:), allocatable :: name
        integer :: j

        j = start
        do while (j <= len(text))
            if (.not. is_name_char(text(j:j))) exit
            j = j + 1
        end do
        name = text(start:j - 1)
    end function identifier_at

    elemental logical function is_name_char(ch)
        character, intent(in) :: ch

        is_name_char = verify(ch, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') == 0
    end function is_name_char

    pure function lower(text) result(low)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: low
        integer :: j

        low = text
        do j = 1, len(text)
            if (text(j:j) >= 'A' .and. text(j:j) <= 'Z') low(j:j) = achar(iachar(text(j:j)) + 32)
        end do
    end function lower

    !> A keyword value as the code compares it: lower case, left-adjusted.
    pure function keyword(text) result(word)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: word

        word = lower(adjustl(text))
    end function keyword

    !> text without blanks (to compare 'a (1)' with 'a(1)').
    pure function squeeze(text) result(packed)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: packed
        integer :: j

        packed = ''
        do j = 1, len(text)
            if (text(j:j) /= ' ') packed = packed // text(j:j)
        end do
    end function squeeze

    !> At most 60 characters of text, for messages.
    pure function excerpt(text) result(short)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: short

        short = trim(adjustl(text))
        if (len(short) > 60) short = short(:57) // '...'
    end function excerpt

    !> text in quotes, unless it is a quoted string already.
    pure function quoted(text) result(q)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: q

        if (scan(text(1:min(1, len(text))), '''"') == 1) then
            q = text
        else
            q = "'" // text // "'"
        end if
    end function quoted

    !> text between two `quote` characters, each `quote` inside it doubled (the quoting of
    !> Fortran strings with "'" and of CSV fields with '"').
    pure function doubled_quotes(text, quote) result(q)
        character(len=*), intent(in) :: text
        character, intent(in) :: quote
        character(len=:), allocatable :: q
        integer :: j

        q = ''
        do j = 1, len(text)
            if (text(j:j) == quote) q = q // quote
            q = q // text(j:j)
        end do
        q = quote // q // quote
    end function doubled_quotes

    pure function int_str(n) result(s)
        integer, intent(in) :: n
        character(len=:), allocatable :: s
        character(len=16) :: buf
        integer :: ios

        write (buf, '(i0)', iostat=ios) n
        s = trim(buf)
    end function int_str

    !> C characters as a Fortran string, up to the first NUL (all of them if there is none).
    pure function from_c_chars(chars) result(text)
        character(kind=c_char), intent(in) :: chars(:)
        character(len=:), allocatable :: text
        integer :: n

        n = findloc(chars, c_null_char, dim=1) - 1
        if (n < 0) n = size(chars)
        text = transfer(chars(1:n), repeat(' ', n))
    end function from_c_chars

end module strings_m
